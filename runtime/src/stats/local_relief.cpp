// Local relief: max - min of height over a square window, as two separable passes (a rectangle's
// extremes are the extremes of its rows' extremes, and clipping at the border is separable too).
#include <algorithm>

#include "stats/field_check.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {

std::vector<float> localRelief(const Heightfield& field, int window) {
    stats::requireField(field);
    TERRASYNTH_REQUIRE(window >= 3 && window % 2 == 1, "relief window must be odd and >= 3");
    const int r = window / 2, w = field.width, h = field.height;
    std::vector<float> row_max(field.size()), row_min(field.size());
    for (int y = 0; y < h; ++y) {
        const float* z = &field.heights[static_cast<size_t>(y) * w];
        for (int x = 0; x < w; ++x) {
            float lo = z[x], hi = z[x];
            for (int k = std::max(0, x - r); k <= std::min(w - 1, x + r); ++k) {
                lo = std::min(lo, z[k]);
                hi = std::max(hi, z[k]);
            }
            row_max[static_cast<size_t>(y) * w + x] = hi;
            row_min[static_cast<size_t>(y) * w + x] = lo;
        }
    }
    std::vector<float> relief(field.size());
    for (int y = 0; y < h; ++y) {
        const int y0 = std::max(0, y - r), y1 = std::min(h - 1, y + r);
        for (int x = 0; x < w; ++x) {
            float lo = row_min[static_cast<size_t>(y) * w + x], hi = row_max[static_cast<size_t>(y) * w + x];
            for (int k = y0; k <= y1; ++k) {
                lo = std::min(lo, row_min[static_cast<size_t>(k) * w + x]);
                hi = std::max(hi, row_max[static_cast<size_t>(k) * w + x]);
            }
            relief[static_cast<size_t>(y) * w + x] = hi - lo;
        }
    }
    return relief;
}

}  // namespace terrasynth
