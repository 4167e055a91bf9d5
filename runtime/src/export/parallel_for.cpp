// parallelFor: the exporters' worker loop.
#include <atomic>
#include <mutex>

#include "core/workers.h"
#include "export/export_internal.h"

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
    runOnWorkers(threads, [&](int) { worker(); });
    return first;
}

}  // namespace terrasynth::export_detail
