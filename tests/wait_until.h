// Waiting in tests: on a condition with a generous deadline, never on a time window, so a loaded
// machine (a shared CI runner, busy loops on every core: scripts/ctest_under_load.sh) only makes a
// test slower, never failing it.
#pragma once

#include <chrono>
#include <thread>

namespace terrasynth::test {

// Calls `done` until it returns true (then true) or `deadline` has passed (then false, for the test
// to report). `done` may do work, e.g. draw a frame; `poll` is the pause between calls.
template <class Condition>
bool waitUntil(Condition done, std::chrono::steady_clock::duration deadline = std::chrono::minutes(10),
               std::chrono::milliseconds poll = std::chrono::milliseconds(1)) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!done()) {
        if (std::chrono::steady_clock::now() > until) return false;
        std::this_thread::sleep_for(poll);
    }
    return true;
}

}  // namespace terrasynth::test
