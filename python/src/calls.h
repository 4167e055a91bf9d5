// How the Python module calls the runtime: without the GIL, stoppable by Ctrl-C, with runtime errors
// turned into Python exceptions, and numbers checked like the command lines check them.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <pybind11/pybind11.h>

#include "terrasynth/argument_checks.h"
#include "terrasynth/grid.h"
#include "terrasynth/status.h"

namespace terrasynth::python {

namespace py = pybind11;

// A runtime error: raised in Python as terrasynth.Error (a RuntimeError) with the runtime's message.
struct RuntimeFailure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The SynthesizerOptions::stop_requested of every synthesizer the module makes. On the thread that
// imported the module (Python's main thread, the only one that runs signal handlers) it takes the
// GIL and runs Python's pending signal handlers (PyErr_CheckSignals); when one raised (Ctrl-C:
// KeyboardInterrupt), the synthesis stops and the exception stays pending for withoutGil to raise.
// Elsewhere it only reports a stop already requested.
std::function<bool()> interruptHook();
// Called once at import with threading.main_thread().ident.
void recordMainThread(unsigned long ident);
// Whether interruptHook stopped a call since the last consumeInterrupt(); clears it.
bool consumeInterrupt();
// Raises the pending KeyboardInterrupt (or whatever the signal handler raised) with a note that the
// synthesis stopped between two pyramid levels. Needs the GIL.
[[noreturn]] void raiseInterrupt();

// Runs `call` (runtime calls only: no Python objects) with the GIL released, so other Python threads
// run meanwhile; re-raises a Ctrl-C that stopped it.
template <class Call>
auto withoutGil(Call&& call) -> decltype(call()) {
    auto result = [&] {
        py::gil_scoped_release release;
        return call();
    }();
    if (consumeInterrupt()) raiseInterrupt();
    return result;
}

inline void check(const Status& status) {
    if (!status) throw RuntimeFailure(status.message());
}
template <class T>
T take(Result<T>&& result) {
    if (!result) throw RuntimeFailure(result.message());
    return std::move(result.value());
}

// checkArgument (argument_checks.h) as a ValueError.
inline void checkNumber(const std::string& name, double value, NumberRange range) {
    if (Status s = checkArgument(name, value, range); !s) throw py::value_error(s.message());
}

// (x, y, width, height) as a window of the global grid, each number checked against the grid's limits.
inline PixelWindow checkedWindow(int64_t x, int64_t y, int64_t width, int64_t height, int min_side = 1) {
    checkNumber("x", static_cast<double>(x), ranges::kWindowOrigin);
    checkNumber("y", static_cast<double>(y), ranges::kWindowOrigin);
    const NumberRange side{static_cast<double>(min_side), ranges::kWindowSide.hi};
    checkNumber("width", static_cast<double>(width), side);
    checkNumber("height", static_cast<double>(height), side);
    return {x, y, static_cast<int>(width), static_cast<int>(height)};
}
using WindowTuple = std::tuple<int64_t, int64_t, int64_t, int64_t>;
// A changed window as Python sees it: (x, y, width, height), or None when nothing changed.
inline std::optional<WindowTuple> windowTuple(const PixelWindow& w) {
    if (w.empty()) return std::nullopt;
    return WindowTuple{w.x, w.y, w.width, w.height};
}

}  // namespace terrasynth::python
