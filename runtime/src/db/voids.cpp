// NoData voids of an exemplar through resampling and the pyramid. The builder never lets synthesis
// copy from a void: void pixels and the kInteriorMargin around them get type kNoType, so they are
// neither PatchMatch matches, nor identity candidates, nor type seeds (database.h).
#include <algorithm>

#include "db/db_internal.h"

namespace terrasynth::db {

std::vector<uint8_t> resampleVoids(const std::vector<uint8_t>& nodata, const Heightfield& original,
                                   double meters_per_pixel) {
    if (nodata.empty()) return {};
    Heightfield share(original.width, original.height, original.meters_per_pixel_x);
    share.meters_per_pixel_y = original.meters_per_pixel_y;
    for (size_t i = 0; i < nodata.size(); ++i) share.heights[i] = nodata[i] ? 1.0f : 0.0f;
    // The same filter as the heights: each resampled pixel's share of void samples.
    const Heightfield resampled = resampleToSpacing(share, meters_per_pixel);
    std::vector<uint8_t> voids(resampled.size());
    for (size_t i = 0; i < voids.size(); ++i) voids[i] = resampled.heights[i] > 1e-3f ? 1 : 0;
    return voids;
}

std::vector<uint8_t> coarserVoids(const std::vector<uint8_t>& fine, int fine_w, int fine_h, int coarse_w, int coarse_h) {
    if (fine.empty()) return {};
    std::vector<uint8_t> coarse(static_cast<size_t>(coarse_w) * coarse_h, 0);
    for (int y = 0; y < coarse_h; ++y)
        for (int x = 0; x < coarse_w; ++x) {
            uint8_t any = 0;  // taps 2p-1 .. 2p+2, clamped like buildGaussianPyramid's
            for (int fy = 2 * y - 1; fy <= 2 * y + 2 && !any; ++fy)
                for (int fx = 2 * x - 1; fx <= 2 * x + 2 && !any; ++fx)
                    any = fine[static_cast<size_t>(std::clamp(fy, 0, fine_h - 1)) * fine_w + std::clamp(fx, 0, fine_w - 1)];
            coarse[static_cast<size_t>(y) * coarse_w + x] = any;
        }
    return coarse;
}

std::vector<uint8_t> voidMargins(const std::vector<uint8_t>& voids, int width, int height) {
    if (voids.empty()) return {};
    // Separable Chebyshev dilation: rows, then columns.
    std::vector<uint8_t> rows(voids.size(), 0), grown(voids.size(), 0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int k = std::max(0, x - kInteriorMargin); k <= std::min(width - 1, x + kInteriorMargin); ++k)
                rows[static_cast<size_t>(y) * width + x] |= voids[static_cast<size_t>(y) * width + k];
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int k = std::max(0, y - kInteriorMargin); k <= std::min(height - 1, y + kInteriorMargin); ++k)
                grown[static_cast<size_t>(y) * width + x] |= rows[static_cast<size_t>(k) * width + x];
    return grown;
}

}  // namespace terrasynth::db
