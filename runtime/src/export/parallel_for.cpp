// parallelFor: the exporters' worker loop.
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "export/export_internal.h"
#include "terrasynth/guard.h"

namespace terrasynth::export_detail {

Status parallelFor(int n, int threads, const std::function<Status(int)>& body) {
    std::atomic<int> next{0};
    std::mutex mutex;
    Status first = Status::ok();
    auto worker = [&] {
        for (int i = next++; i < n; i = next++) {
            Status s = body(i);
            if (!s) {
                std::lock_guard<std::mutex> lock(mutex);
                if (first) first = s;
                next = n;
            }
        }
    };
    std::vector<std::thread> pool;
    FirstException thrown;  // rethrown here, never std::terminate in a worker
    for (int t = 1; t < threads; ++t) pool.emplace_back([&] { thrown.run(worker); });
    thrown.run(worker);
    for (std::thread& t : pool) t.join();
    thrown.rethrow();
    return first;
}

}  // namespace terrasynth::export_detail
