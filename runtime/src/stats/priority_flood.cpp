// Priority-Flood (Barnes, Lehman & Mulla 2014, "Priority-Flood: An optimal depression-filling and
// watershed-labeling algorithm for digital elevation models", Alg. 2 and 3).
//
// Water leaves the field through its border, so the border cells seed a min-priority queue. Cells are
// then taken lowest first; each unvisited neighbour that is not higher than the cell taken lies in a
// depression (or on a flat) and is raised to the cell's level (or one epsilon step above it) and put on
// a plain FIFO "pit" queue: its levels only grow, so it needs no heap, and comparing its front with
// the heap's top keeps the global order. That keeps the common case O(n) and the worst case O(n log n).
#include "stats/priority_flood.h"

#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "terrasynth/heightfield.h"

namespace terrasynth::stats {

template <class T>
void priorityFlood(std::vector<T>& z, int width, int height, bool epsilon) {
    TERRASYNTH_REQUIRE(width > 0 && height > 0 && z.size() == static_cast<size_t>(width) * height,
                       "priority flood needs a grid whose sample count matches its size");
    using Cell = std::pair<T, int32_t>;  // ties broken by index, so the result is deterministic
    std::priority_queue<Cell, std::vector<Cell>, std::greater<Cell>> open;
    std::deque<int32_t> pit;
    std::vector<uint8_t> closed(z.size(), 0);

    auto seed = [&](int x, int y) {
        const int32_t i = y * width + x;
        if (closed[i]) return;
        closed[i] = 1;
        open.push({z[i], i});
    };
    for (int x = 0; x < width; ++x) {
        seed(x, 0);
        seed(x, height - 1);
    }
    for (int y = 0; y < height; ++y) {
        seed(0, y);
        seed(width - 1, y);
    }

    static const int kDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
    static const int kDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
    const T infinity = std::numeric_limits<T>::infinity();
    while (!open.empty() || !pit.empty()) {
        int32_t c;
        // Take the lower of the two queue fronts, an open cell on ties (Alg. 3), so cells leave in
        // non-decreasing order even when epsilon steps carry the pit queue above the open queue's top;
        // that order is what makes a second fill change nothing.
        if (!pit.empty() && (open.empty() || z[pit.front()] < open.top().first)) {
            c = pit.front();
            pit.pop_front();
        } else {
            c = open.top().second;
            open.pop();
        }
        const int cx = c % width, cy = c / width;
        const T level = epsilon ? std::nextafter(z[c], infinity) : z[c];
        for (int k = 0; k < 8; ++k) {
            const int nx = cx + kDx[k], ny = cy + kDy[k];
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            const int32_t n = ny * width + nx;
            if (closed[n]) continue;
            closed[n] = 1;
            if (z[n] <= level) {
                z[n] = level;
                pit.push_back(n);
            } else {
                open.push({z[n], n});
            }
        }
    }
}

template void priorityFlood<float>(std::vector<float>&, int, int, bool);
template void priorityFlood<double>(std::vector<double>&, int, int, bool);

}  // namespace terrasynth::stats
