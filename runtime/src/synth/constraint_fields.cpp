#include "synth/constraint_fields.h"

#include <algorithm>
#include <cmath>

#include "synth/hash.h"

namespace terrasynth::synth {

LevelConstraints constraintsForLevel(const SynthesisConstraints* constraints, int level, const LevelRegion& region) {
    LevelConstraints out;
    if (!constraints || level < kFirstConstrainedLevel) return out;
    const double kDegree = 3.14159265358979323846 / 180.0;
    for (const PointConstraint& p : constraints->points) {
        const double rise = std::tan(p.slope_angle_deg * kDegree);
        const double direction = p.slope_direction_deg * kDegree;  // clockwise from north
        out.points.insert(out.points.end(),
                          {static_cast<float>(p.x), static_cast<float>(p.y), p.height_m,
                           static_cast<float>(rise * std::sin(direction)), static_cast<float>(-rise * std::cos(direction)),
                           p.radius_px, 0.0f, 0.0f});
    }
    const TypePaint& paint = constraints->types;
    if (paint.empty()) return out;
    const int64_t cell = int64_t(1) << level;
    // Level-0 bounds of the region; skip the work when the painting is elsewhere.
    const int64_t x0 = region.x * cell, y0 = region.y * cell;
    const int64_t x1 = (int64_t(region.x) + region.width) * cell, y1 = (int64_t(region.y) + region.height) * cell;
    if (x1 <= paint.x || y1 <= paint.y || x0 >= paint.x + paint.width || y0 >= paint.y + paint.height) return out;
    out.target_sets.assign(region.pixels(), 0u);
    bool any = false;
    for (int py = 0; py < paint.height; ++py) {
        const int64_t gy = paint.y + py;
        const int64_t ly = (gy >> level) - region.y;  // arithmetic shift = floor division
        if (ly < 0 || ly >= region.height) continue;
        for (int px = 0; px < paint.width; ++px) {
            const uint8_t t = paint.types[static_cast<size_t>(py) * paint.width + px];
            if (t == TypePaint::kUnpainted || t >= kMaxPaintableTypes) continue;
            const int64_t lx = ((paint.x + px) >> level) - region.x;
            if (lx < 0 || lx >= region.width) continue;
            out.target_sets[static_cast<size_t>(ly) * region.width + lx] |= 1u << t;
            any = true;
        }
    }
    if (!any) out.target_sets.clear();
    return out;
}

SeedTable seedTable(const DatabaseLevel& level) {
    SeedTable table;
    table.ranges.assign(2 * kMaxPaintableTypes, 0);
    for (size_t t = 0; t < level.type_seeds.size() && t < static_cast<size_t>(kMaxPaintableTypes); ++t) {
        table.ranges[2 * t] = static_cast<int32_t>(table.seeds.size());
        table.ranges[2 * t + 1] = static_cast<int32_t>(level.type_seeds[t].size());
        table.seeds.insert(table.seeds.end(), level.type_seeds[t].begin(), level.type_seeds[t].end());
    }
    if (table.seeds.empty()) table.seeds.push_back(0);
    return table;
}

uint32_t seedingSalt(uint32_t seed, int level) { return levelSalt(seed, level, 3); }

}  // namespace terrasynth::synth
