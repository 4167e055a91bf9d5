// Row-parallel loops for the layer module (core/workers.h), deterministic results because every
// row is computed by exactly one worker from the same inputs regardless of scheduling.
#pragma once

#include <algorithm>
#include <atomic>

#include "core/workers.h"

namespace terrasynth::layers {

// Calls fn(begin, end) over disjoint blocks of [0, n). Runs inline when the work is small
// (`cost_per_item` * n below ~2^16) so tiny pyramid levels do not pay thread start-up.
template <class Fn>
void parallelFor(int n, long cost_per_item, Fn&& fn) {
    if (n <= 0) return;
    const int hw = hardwareThreads();
    const long total = static_cast<long>(n) * std::max(1L, cost_per_item);
    if (hw == 1 || total < (1L << 16) || n < 4) {
        fn(0, n);
        return;
    }
    const int workers = std::min(hw, 8);
    const int block = std::max(1, n / (workers * 4));
    std::atomic<int> next{0};
    runOnWorkers(workers, [&](int) {
        for (;;) {
            const int begin = next.fetch_add(block);
            if (begin >= n) return;
            fn(begin, std::min(n, begin + block));
        }
    });
}

}  // namespace terrasynth::layers
