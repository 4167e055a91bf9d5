// Row-parallel loops for the layer module: plain std::thread, deterministic results because every
// row is computed by exactly one worker from the same inputs regardless of scheduling.
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "terrasynth/guard.h"

namespace terrasynth::layers {

// Calls fn(begin, end) over disjoint blocks of [0, n). Runs inline when the work is small
// (`cost_per_item` * n below ~2^16) so tiny pyramid levels do not pay thread start-up.
template <class Fn>
void parallelFor(int n, long cost_per_item, Fn&& fn) {
    if (n <= 0) return;
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const long total = static_cast<long>(n) * std::max(1L, cost_per_item);
    if (hw == 1 || total < (1L << 16) || n < 4) {
        fn(0, n);
        return;
    }
    const int workers = static_cast<int>(std::min<unsigned>(hw, 8u));
    const int block = std::max(1, n / (workers * 4));
    std::atomic<int> next{0};
    auto run = [&] {
        for (;;) {
            const int begin = next.fetch_add(block);
            if (begin >= n) return;
            fn(begin, std::min(n, begin + block));
        }
    };
    std::vector<std::thread> threads;
    threads.reserve(workers - 1);
    FirstException first;  // rethrown here, never std::terminate in a worker
    for (int t = 1; t < workers; ++t) threads.emplace_back([&] { first.run(run); });
    first.run(run);
    for (auto& t : threads) t.join();
    first.rethrow();
}

}  // namespace terrasynth::layers
