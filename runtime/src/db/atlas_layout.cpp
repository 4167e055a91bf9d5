// Shelf packing: exemplars sorted by height go left to right in rows of a fixed width, each with a
// gutter so bilinear taps and 5x5 windows near an edge never read another exemplar.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "db/db_internal.h"

namespace terrasynth::db {

AtlasLayout packAtlas(const std::vector<std::pair<int, int>>& sizes) {
    AtlasLayout layout;
    layout.rects.resize(sizes.size());
    if (sizes.empty()) return layout;
    size_t area = 0;
    int widest = 0;
    for (auto [w, h] : sizes) {
        area += static_cast<size_t>(w + 2 * kAtlasGutter) * (h + 2 * kAtlasGutter);
        widest = std::max(widest, w + 2 * kAtlasGutter);
    }
    // Aim for a roughly square atlas, never narrower than the widest exemplar.
    const int row_width = std::max(widest, static_cast<int>(std::sqrt(static_cast<double>(area)) * 1.1));
    std::vector<size_t> order(sizes.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sizes[a].second > sizes[b].second; });
    int x = 0, y = 0, shelf_height = 0;
    for (size_t i : order) {
        const int w = sizes[i].first + 2 * kAtlasGutter, h = sizes[i].second + 2 * kAtlasGutter;
        if (x + w > row_width) {
            x = 0;
            y += shelf_height;
            shelf_height = 0;
        }
        layout.rects[i] = {x + kAtlasGutter, y + kAtlasGutter, sizes[i].first, sizes[i].second};
        x += w;
        shelf_height = std::max(shelf_height, h);
        layout.width = std::max(layout.width, x);
    }
    layout.height = y + shelf_height;
    return layout;
}

}  // namespace terrasynth::db
