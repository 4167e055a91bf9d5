// Private: the runtime's one way to run work on several threads. Worker 0 runs on the calling
// thread and every other on a std::thread of its own; an exception in any worker is rethrown on the
// calling thread once all have joined (terrasynth/guard.h, FirstException), never std::terminate.
// The modules' loops (db::parallelRows, layers::parallelFor, export_detail::parallelFor, the
// drainage breach's pit search) are built on it.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

#include "terrasynth/guard.h"

namespace terrasynth {

// Threads the machine runs at once: std::thread::hardware_concurrency, at least 1.
inline int hardwareThreads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

// Calls work(worker) for every worker in [0, workers) at once and returns when all have returned.
// Deterministic results are the caller's part: split the work by worker index (or hand out items
// whose results do not depend on who takes them), never by arrival order. workers < 1 counts as 1.
// A thread that cannot be started leaves its workers to the calling thread, after worker 0.
template <class Work>
void runOnWorkers(int workers, Work&& work) {
    workers = std::max(1, workers);
    FirstException first;
    std::vector<std::thread> pool;
    int started = 1;
    try {
        pool.reserve(static_cast<size_t>(workers - 1));
        for (; started < workers; ++started) {
            const int worker = started;
            pool.emplace_back([&first, &work, worker] { first.run([&] { work(worker); }); });
        }
    } catch (...) {  // out of threads or memory: the calling thread takes the rest
    }
    first.run([&] { work(0); });
    for (int worker = started; worker < workers; ++worker) first.run([&] { work(worker); });
    for (std::thread& t : pool) t.join();
    first.rethrow();
}

}  // namespace terrasynth
