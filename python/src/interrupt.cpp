// Ctrl-C for long runtime calls: the synthesizers ask interruptHook() before each pyramid level
// (SynthesizerOptions::stop_requested), and it lets Python run its signal handlers there.
#include <pybind11/pybind11.h>

#include "calls.h"

namespace terrasynth::python {
namespace {

unsigned long main_thread = 0;
// Set when a signal handler raised during a call; the exception is pending on the main thread.
std::atomic<bool> interrupted{false};

bool stopRequested() {
    if (interrupted.load()) return true;
    if (PyThread_get_thread_ident() != main_thread) return false;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() == 0) return false;
    interrupted.store(true);
    return true;
}

}  // namespace

void recordMainThread(unsigned long ident) { main_thread = ident; }

std::function<bool()> interruptHook() { return stopRequested; }

bool consumeInterrupt() {
    // Only the main thread's call owns the pending exception; a call of another thread stopped by it
    // fails with the runtime's "synthesis stopped" error instead.
    if (PyThread_get_thread_ident() != main_thread) return false;
    return interrupted.exchange(false);
}

void raiseInterrupt() {
    if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
    PyObject *type = nullptr, *value = nullptr, *trace = nullptr;
    PyErr_Fetch(&type, &value, &trace);
    PyErr_NormalizeException(&type, &value, &trace);
    if (trace) PyException_SetTraceback(value, trace);
    PyObject* noted = PyObject_CallMethod(value, "add_note", "s",
                                          "terrasynth: the synthesis stopped between two pyramid levels");
    if (noted) Py_DECREF(noted);
    else PyErr_Clear();  // Python before 3.11: no notes
    PyErr_Restore(type, value, trace);
    throw py::error_already_set();
}

}  // namespace terrasynth::python
