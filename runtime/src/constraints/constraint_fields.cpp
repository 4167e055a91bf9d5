#include "constraints/constraint_fields.h"

#include <algorithm>
#include <cmath>

#include "constraints/curve_field.h"

namespace terrasynth::constraints {

namespace {
double smoothstep(double a) {
    a = std::clamp(a, 0.0, 1.0);
    return a * a * (3.0 - 2.0 * a);
}
}  // namespace

void accumulatePoint(const PointConstraint& point, int level, const core::LevelRegion& region, double meters_per_pixel0,
                     float sign, std::vector<float>& blend, double localisation_px) {
    const double cell = std::ldexp(1.0, level);
    // s5.1 shrinks a point's area of effect at finer levels to min(radius, 4 * 2^level) px. Here it
    // keeps the whole radius on every constrained level: the tolerance of phi_d grows with the
    // distance from the site (0.5 m per pixel), so the plane only pulls where the terrain strays
    // far from it, and with the paper's localisation the outer half of the radius was held on one
    // or two levels only, so the slope direction over half the radius was the terrain's draw
    // (docs/realism.md, "Where synthesis starts": worst of 40 points 11.3 deg off, 3.8 now).
    const double reach = localisation_px > 0.0 ? std::min<double>(point.radius_px, localisation_px) : point.radius_px;
    // Level-i pixels whose centres ((p + 0.5) * cell - 0.5) can be within reach.
    const int x0 = std::max(region.x, static_cast<int>(std::floor((point.x - reach + 0.5) / cell - 0.5)));
    const int x1 = std::min(region.x + region.width - 1, static_cast<int>(std::ceil((point.x + reach + 0.5) / cell - 0.5)));
    const int y0 = std::max(region.y, static_cast<int>(std::floor((point.y - reach + 0.5) / cell - 0.5)));
    const int y1 = std::min(region.y + region.height - 1, static_cast<int>(std::ceil((point.y + reach + 0.5) / cell - 0.5)));
    // Most points are far from a small window (point lifting synthesizes many): skip them before
    // any trigonometry.
    if (x0 > x1 || y0 > y1) return;
    const double kDegree = 3.14159265358979323846 / 180.0;
    const double rise = std::tan(point.slope_angle_deg * kDegree);
    const double direction = point.slope_direction_deg * kDegree;  // clockwise from north, rising
    const double rise_east = rise * std::sin(direction), rise_south = -rise * std::cos(direction);
    for (int gy = y0; gy <= y1; ++gy) {
        for (int gx = x0; gx <= x1; ++gx) {
            const double ex = (gx + 0.5) * cell - 0.5 - point.x, ey = (gy + 0.5) * cell - 0.5 - point.y;
            const double d = std::sqrt(ex * ex + ey * ey);
            if (d >= reach) continue;
            const double b = 1.0 / std::max(d, 0.5);
            // The tilt lift holds the slope over the site's own pixels and fades out beyond them,
            // where the wide tilt lift takes over.
            const double tilt = 1.0 - smoothstep((d - kSiteHalfWidthPx) / kSiteHalfWidthPx);
            const double east = rise_east + tilt * point.tilt_east + (1.0 - tilt) * point.wide_tilt_east;
            const double south = rise_south + tilt * point.tilt_south + (1.0 - tilt) * point.wide_tilt_south;
            const double target = point.height_m + point.lift_m + (east * ex + south * ey) * meters_per_pixel0;
            float* sums = &blend[(static_cast<size_t>(gy - region.y) * region.width + (gx - region.x)) * 4];
            sums[0] += sign * static_cast<float>(b);
            sums[1] += sign * static_cast<float>(b * target);
            sums[2] += sign * static_cast<float>(b * d);
        }
    }
}

namespace {

// Whether any pixel of 4-float blend sums got a constraint.
bool anyBlend(const std::vector<float>& blend) {
    for (size_t i = 0; i < blend.size(); i += 4)
        if (blend[i] > 0.0f) return true;
    return false;
}

void addCurveSums(const std::vector<CurveConstraint>& curves, int level, const core::LevelRegion& region, double meters_per_pixel0,
                  bool held_free_level, std::vector<float>& blend) {
    std::vector<float> sums(region.pixels() * 3, 0.0f);
    accumulateCurves(curves, level, region, meters_per_pixel0, sums, held_free_level);
    for (size_t i = 0; i < region.pixels(); ++i)
        for (int k = 0; k < 3; ++k) blend[i * 4 + k] += sums[i * 3 + k];
}

// A free level with held own pixels (s5.1 leaves these levels free): the points' 7x7 sites, and the
// curves held softly (curve_raster.h).
LevelConstraints heldOwnPixels(const SynthesisConstraints& constraints, int level, const core::LevelRegion& region,
                               double meters_per_pixel0) {
    LevelConstraints out;
    if (constraints.points.empty() && constraints.curves.empty()) return out;
    out.blend.assign(region.pixels() * 4, 0.0f);
    for (const PointConstraint& p : constraints.points)
        accumulatePoint(p, level, region, meters_per_pixel0, 1.0f, out.blend, kSiteHalfWidthPx);
    if (!constraints.curves.empty()) addCurveSums(constraints.curves, level, region, meters_per_pixel0, true, out.blend);
    if (!anyBlend(out.blend)) out.blend.clear();
    return out;
}

}  // namespace

LevelConstraints constraintsForLevel(const SynthesisConstraints* constraints, int level, int first_level,
                                     bool hold_free_levels, const core::LevelRegion& region, double meters_per_pixel0) {
    LevelConstraints out;
    if (!constraints) return out;
    if (level < first_level) {
        if (hold_free_levels) out = heldOwnPixels(*constraints, level, region, meters_per_pixel0);
        out.target_sets = paintedTargetSets(constraints->types, level, region);
        out.types_keep_only = true;
        return out;
    }
    if (!constraints->points.empty() || !constraints->curves.empty()) {
        out.blend.assign(region.pixels() * 4, 0.0f);
        for (const PointConstraint& p : constraints->points) accumulatePoint(p, level, region, meters_per_pixel0, 1.0f, out.blend);
        if (!constraints->curves.empty()) addCurveSums(constraints->curves, level, region, meters_per_pixel0, false, out.blend);
        if (!anyBlend(out.blend)) out.blend.clear();
    }
    out.target_sets = paintedTargetSets(constraints->types, level, region);
    return out;
}

std::vector<uint32_t> paintedTargetSets(const TypePaint& paint, int level, const core::LevelRegion& region) {
    if (paint.empty()) return {};
    const int64_t cell = int64_t(1) << level;
    // Level-0 bounds of the region; skip the work when the painting is elsewhere.
    const int64_t x0 = region.x * cell, y0 = region.y * cell;
    const int64_t x1 = (int64_t(region.x) + region.width) * cell, y1 = (int64_t(region.y) + region.height) * cell;
    if (x1 <= paint.x || y1 <= paint.y || x0 >= paint.x + paint.width || y0 >= paint.y + paint.height) return {};
    std::vector<uint32_t> sets(region.pixels(), 0u);
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
            sets[static_cast<size_t>(ly) * region.width + lx] |= 1u << t;
            any = true;
        }
    }
    if (!any) sets.clear();
    return sets;
}

}  // namespace terrasynth::constraints
