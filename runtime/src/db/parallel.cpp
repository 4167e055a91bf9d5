#include <algorithm>
#include <thread>

#include "db/db_internal.h"

namespace terrasynth::db {

void parallelRows(int rows, int threads, const std::function<void(int, int)>& body) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::max(1, std::min(threads, rows));
    if (threads == 1) {
        body(0, rows);
        return;
    }
    std::vector<std::thread> pool;
    const int chunk = (rows + threads - 1) / threads;
    for (int t = 0; t < threads; ++t) {
        const int begin = t * chunk, end = std::min(rows, begin + chunk);
        if (begin < end) pool.emplace_back(body, begin, end);
    }
    for (auto& th : pool) th.join();
}

}  // namespace terrasynth::db
