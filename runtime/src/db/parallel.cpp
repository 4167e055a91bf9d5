#include <algorithm>
#include <thread>

#include "db/db_internal.h"
#include "terrasynth/guard.h"

namespace terrasynth::db {

void parallelRows(int rows, int threads, const std::function<void(int, int)>& body) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::max(1, std::min(threads, rows));
    if (threads == 1) {
        body(0, rows);
        return;
    }
    std::vector<std::thread> pool;
    FirstException first;  // rethrown here, never std::terminate in a worker
    const int chunk = (rows + threads - 1) / threads;
    for (int t = 0; t < threads; ++t) {
        const int begin = t * chunk, end = std::min(rows, begin + chunk);
        if (begin < end) pool.emplace_back([&, begin, end] { first.run([&] { body(begin, end); }); });
    }
    for (auto& th : pool) th.join();
    first.rethrow();
}

}  // namespace terrasynth::db
