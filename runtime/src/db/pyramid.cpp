#include "db/db_internal.h"

namespace terrasynth::db {

std::vector<Heightfield> buildGaussianPyramid(const Heightfield& base, int levels) {
    std::vector<Heightfield> pyramid;
    pyramid.push_back(base);
    for (int i = 1; i <= levels; ++i) {
        const Heightfield& fine = pyramid.back();
        const int w = fine.width / 2, h = fine.height / 2;
        if (w < 1 || h < 1) break;
        // Separable binomial [1 3 3 1]/8 centred on fine coordinate 2p + 0.5.
        Heightfield rows(w, fine.height, fine.meters_per_pixel_x * 2.0);
        for (int y = 0; y < fine.height; ++y)
            for (int x = 0; x < w; ++x)
                rows.at(x, y) = (fine.clamped(2 * x - 1, y) + 3.0f * fine.clamped(2 * x, y) +
                                 3.0f * fine.clamped(2 * x + 1, y) + fine.clamped(2 * x + 2, y)) * 0.125f;
        Heightfield coarse(w, h, fine.meters_per_pixel_x * 2.0);
        coarse.meters_per_pixel_y = fine.meters_per_pixel_y * 2.0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                coarse.at(x, y) = (rows.clamped(x, 2 * y - 1) + 3.0f * rows.clamped(x, 2 * y) +
                                   3.0f * rows.clamped(x, 2 * y + 1) + rows.clamped(x, 2 * y + 2)) * 0.125f;
        pyramid.push_back(std::move(coarse));
    }
    return pyramid;
}

}  // namespace terrasynth::db
