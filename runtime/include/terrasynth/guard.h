// terrasynth/guard.h: the last line of defence at the entry points of programs and plugins.
//
// The runtime reports bad input as Status and never throws across its API, but the standard
// library still can (std::bad_alloc when memory runs out, std::length_error) and so can the
// libraries around it (CLI11, OSG, ImGui). Every entry point (a main(), an osgDB ReaderWriter call,
// an editor action, a game's frame) wraps its body once, so any exception becomes a message and a
// failure instead of std::terminate:
//
//   int main(int argc, char** argv) {
//       return terrasynth::runGuarded("terrasynth", [&] { return run(argc, argv); });
//   }
//   // osgDB: the exception becomes the ReadResult's error message.
//   return terrasynth::invokeGuarded([&] { return read(file, options); },
//                                    [&](const std::string& why) { return ReadResult(file + ": " + why); });
//   // An editor button: the message lands where the editor shows errors.
//   Status s = terrasynth::guarded("save", [&] { return session.save(); });
//
// Threading: all of it is re-entrant. An exception leaving a std::thread calls std::terminate, so
// thread pools run each worker's body through FirstException and rethrow on the thread that waits
// for them, where the entry point's guard sees it.
#pragma once

#include <cstdio>
#include <exception>
#include <mutex>
#include <string>
#include <utility>

#include "terrasynth/status.h"

namespace terrasynth {

// The exception being handled, as one line: "out of memory (std::bad_alloc)", a std::exception's
// what(), or "unknown exception". Call it only inside a catch block.
std::string describeCurrentException();

// Returns body(); if body throws, returns on_exception(describeCurrentException()) instead.
template <class Body, class OnException>
auto invokeGuarded(Body&& body, OnException&& on_exception) -> decltype(body()) {
    try {
        return std::forward<Body>(body)();
    } catch (...) {
        return std::forward<OnException>(on_exception)(describeCurrentException());
    }
}

// For bodies returning Status: an exception becomes Status::error("<context>: <description>").
template <class Body>
Status guarded(const std::string& context, Body&& body) {
    return invokeGuarded(std::forward<Body>(body),
                         [&](const std::string& why) { return Status::error(context + ": " + why); });
}

// For main(): returns body()'s exit code; an exception prints "<program>: <description>" to stderr
// and returns 1.
template <class Body>
int runGuarded(const char* program, Body&& body) {
    return invokeGuarded(std::forward<Body>(body), [&](const std::string& why) {
        std::fprintf(stderr, "%s: %s\n", program, why.c_str());
        return 1;
    });
}

// Keeps the first exception thrown by any worker of a pool:
//   FirstException first;
//   for (...) threads.emplace_back([&] { first.run([&] { work(); }); });
//   for (auto& t : threads) t.join();
//   first.rethrow();  // on the waiting thread, if any worker threw
class FirstException {
public:
    template <class Body>
    void run(Body&& body) noexcept {
        try {
            std::forward<Body>(body)();
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex_);
            if (!first_) first_ = std::current_exception();
        }
    }
    bool caught() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return static_cast<bool>(first_);
    }
    void rethrow() const {
        std::lock_guard<std::mutex> lock(mutex_);
        if (first_) std::rethrow_exception(first_);
    }

private:
    mutable std::mutex mutex_;
    std::exception_ptr first_;
};

}  // namespace terrasynth
