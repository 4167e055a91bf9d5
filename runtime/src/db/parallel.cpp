#include <algorithm>

#include "core/workers.h"
#include "db/db_internal.h"

namespace terrasynth::db {

void parallelRows(int rows, int threads, const std::function<void(int, int)>& body) {
    if (threads <= 0) threads = hardwareThreads();
    threads = std::max(1, std::min(threads, rows));
    if (threads == 1) {
        body(0, rows);
        return;
    }
    const int chunk = (rows + threads - 1) / threads;
    runOnWorkers(threads, [&](int t) {
        const int begin = t * chunk, end = std::min(rows, begin + chunk);
        if (begin < end) body(begin, end);
    });
}

}  // namespace terrasynth::db
