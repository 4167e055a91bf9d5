#include "thumbnails.h"

#include <algorithm>
#include <cmath>

namespace terrasynth::editor {

Picture hillshadePicture(const Heightfield& field, int max_side) {
    Picture out;
    if (field.empty()) return out;
    const int step = std::max(1, (std::max(field.width, field.height) + max_side - 1) / max_side);
    out.width = std::max(1, field.width / step);
    out.height = std::max(1, field.height / step);
    out.rgba.assign(static_cast<size_t>(out.width) * out.height * 4, 255);
    const HeightRange range = heightRange(field);
    const float span = std::max(range.max - range.min, 1.0f);
    // Sun from the north-west at 45 degrees: light vector (-1, -1 south-positive y, up).
    const double lx = -0.5, ly = -0.5, lz = std::sqrt(0.5);
    const double spacing = field.meters_per_pixel_x * step;
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            const int fx = x * step, fy = y * step;
            const double dzdx = (field.clamped(fx + step, fy) - field.clamped(fx - step, fy)) / (2.0 * spacing);
            const double dzdy = (field.clamped(fx, fy + step) - field.clamped(fx, fy - step)) / (2.0 * spacing);
            const double nx = -dzdx, ny = -dzdy, nz = 1.0;
            const double shade = std::clamp((nx * lx + ny * ly + nz * lz) / std::sqrt(nx * nx + ny * ny + nz * nz), 0.0, 1.0);
            const double h = (field.at(fx, fy) - range.min) / span;
            // Green lowland -> brown upland -> white top.
            const double r = h < 0.5 ? 0.35 + 0.5 * h : 0.6 + 0.8 * (h - 0.5);
            const double g = h < 0.5 ? 0.55 - 0.1 * h : 0.5 + 0.9 * (h - 0.5);
            const double b = h < 0.5 ? 0.30 : 0.3 + 1.3 * (h - 0.5);
            const double light = 0.35 + 0.65 * shade;
            uint8_t* p = &out.rgba[(static_cast<size_t>(y) * out.width + x) * 4];
            p[0] = static_cast<uint8_t>(std::clamp(255.0 * r * light, 0.0, 255.0));
            p[1] = static_cast<uint8_t>(std::clamp(255.0 * g * light, 0.0, 255.0));
            p[2] = static_cast<uint8_t>(std::clamp(255.0 * b * light, 0.0, 255.0));
        }
    }
    return out;
}

Heightfield exemplarHeights(const ExemplarDatabase& db, int exemplar) {
    if (db.levels.empty() || exemplar < 0 || exemplar >= static_cast<int>(db.levels[0].rects.size())) return {};
    const DatabaseLevel& level = db.levels[0];
    const AtlasRect& r = level.rects[static_cast<size_t>(exemplar)];
    Heightfield out(r.width, r.height, db.meters_per_pixel);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            out.at(x, y) = level.height_m[static_cast<size_t>(r.y + y) * level.width + static_cast<size_t>(r.x + x)];
    return out;
}

}  // namespace terrasynth::editor
