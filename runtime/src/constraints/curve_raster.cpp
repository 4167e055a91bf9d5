// One curve constraint rasterised into a level's blend sums (Gain et al. 2015 s5.1): "A pixel within
// the curve's envelope of effect is attached to the nearest point on the curve C(t) and the properties
// at parameter t are fed to the same process as before (Equations 8, 9)."
#include "constraints/curve_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "terrasynth/status.h"

namespace terrasynth::constraints {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The course at a level's resolution: samples at least a quarter level pixel apart along the arc
// (chords of a few level-0 pixels deviate from the spline by far less than a level pixel).
struct LevelCourse {
    std::vector<double> x, y, s;
    bool closed = false;
    size_t segments() const { return x.size() - 1; }
};

LevelCourse decimate(const CourseSamples& c, double step_px) {
    LevelCourse out;
    out.closed = c.closed;
    const size_t n = c.x.size();
    for (size_t i = 0; i < n; ++i) {
        if (i > 0 && i + 1 < n && c.s[i] - out.s.back() < step_px) continue;
        out.x.push_back(c.x[i]);
        out.y.push_back(c.y[i]);
        out.s.push_back(c.s[i]);
    }
    return out;
}

// Level-0 coordinate of the centre of level pixel p (curve_field.h).
double centre(int p, double cell) { return (p + 0.5) * cell - 0.5; }

// The distance field of s5.1 over the working grid: per pixel the closest segment and its parameter,
// found by scanning each segment's neighbourhood (the envelope is a narrow band around the course).
struct ClosestField {
    std::vector<double> dist2, u;
    std::vector<int> segment;
};

ClosestField closestField(const LevelCourse& c, const EnvelopeGrid& g, double cell, double reach_px) {
    ClosestField field;
    const size_t n = static_cast<size_t>(g.width) * g.height;
    field.dist2.assign(n, std::numeric_limits<double>::infinity());
    field.u.assign(n, 0.0);
    field.segment.assign(n, -1);
    const double reach2 = reach_px * reach_px;
    for (size_t i = 0; i < c.segments(); ++i) {
        const double ax = c.x[i], ay = c.y[i], ex = c.x[i + 1] - ax, ey = c.y[i + 1] - ay;
        const double len2 = ex * ex + ey * ey;
        const int px0 = std::max(g.x0, static_cast<int>(std::ceil((std::min(ax, ax + ex) - reach_px + 0.5) / cell - 0.5)));
        const int px1 = std::min(g.x0 + g.width - 1, static_cast<int>(std::floor((std::max(ax, ax + ex) + reach_px + 0.5) / cell - 0.5)));
        const int py0 = std::max(g.y0, static_cast<int>(std::ceil((std::min(ay, ay + ey) - reach_px + 0.5) / cell - 0.5)));
        const int py1 = std::min(g.y0 + g.height - 1, static_cast<int>(std::floor((std::max(ay, ay + ey) + reach_px + 0.5) / cell - 0.5)));
        for (int py = py0; py <= py1; ++py) {
            const double qy = centre(py, cell);
            for (int px = px0; px <= px1; ++px) {
                const double qx = centre(px, cell);
                double u = len2 > 0.0 ? ((qx - ax) * ex + (qy - ay) * ey) / len2 : 0.0;
                u = std::clamp(u, 0.0, 1.0);
                const double dx = qx - (ax + u * ex), dy = qy - (ay + u * ey);
                const double d2 = dx * dx + dy * dy;
                const size_t k = static_cast<size_t>(py - g.y0) * g.width + (px - g.x0);
                if (d2 < field.dist2[k] && d2 <= reach2) {  // strict: ties keep the earlier segment
                    field.dist2[k] = d2;
                    field.u[k] = u;
                    field.segment[k] = static_cast<int>(i);
                }
            }
        }
    }
    return field;
}

// What a pixel attached to the course receives: side (or cap) reach and gradient, height at t (with
// the curve's lift).
struct Attachment {
    double s = 0.0, reach = 0.0, gradient = 0.0, height = 0.0;
};

Attachment attach(const LevelCourse& c, const CurveProfile& profile, size_t segment, double u, double qx, double qy) {
    const double ex = c.x[segment + 1] - c.x[segment], ey = c.y[segment + 1] - c.y[segment];
    const double len = std::hypot(ex, ey);
    const double tx = ex / len, ty = ey / len;
    const double lx = ty, ly = -tx;  // left normal (x east, y south: left of east is north)
    const double vx = qx - (c.x[segment] + u * ex), vy = qy - (c.y[segment] + u * ey);
    Attachment a;
    a.s = c.s[segment] + u * (c.s[segment + 1] - c.s[segment]);
    const CurveProperties p = profile.at(a.s);
    a.height = p.height + profile.liftAt(a.s);
    const double along = vx * tx + vy * ty, left = vx * lx + vy * ly;
    const bool start_cap = !c.closed && segment == 0 && u <= 0.0 && along < 0.0;
    const bool end_cap = !c.closed && segment + 1 == c.segments() && u >= 1.0 && along > 0.0;
    if (start_cap || end_cap) {
        // Angle around the endpoint from the right side line (0) through straight ahead to the left (1).
        const double ahead = start_cap ? -along : along;
        const CurveProperties cap = capProperties(p, std::atan2(left, ahead) / kPi + 0.5);
        a.reach = cap.left_reach;
        a.gradient = cap.left_gradient;
    } else if (left >= 0.0) {
        a.reach = p.left_reach;
        a.gradient = p.left_gradient;
    } else {
        a.reach = p.right_reach;
        a.gradient = p.right_gradient;
    }
    return a;
}

double maxReach(const LevelCourse& c, const CurveProfile& profile) {
    double r = 0.0;
    for (double s : c.s) {
        const CurveProperties p = profile.widgetsAt(profile.t(s));
        r = std::max({r, p.left_reach, p.right_reach});
    }
    return r;
}

}  // namespace

EnvelopeSmoothing envelopeSmoothingForLevel(int level, double max_reach_px) {
    const double cell = std::ldexp(1.0, level);
    EnvelopeSmoothing s;
    s.jump_arc_px = 3.0 * cell;
    s.window = std::max(4, static_cast<int>(std::ceil(2.0 * max_reach_px / cell)));
    return s;
}

void accumulateCurve(const CourseSamples& course, const CurveProfile& profile, int level, const core::LevelRegion& region,
                     double meters_per_pixel0, bool smooth, std::vector<float>& sums, bool held_free_level) {
    TERRASYNTH_REQUIRE(sums.size() == 3 * region.pixels(), "accumulateCurve: sums must hold 3 floats per region pixel");
    TERRASYNTH_REQUIRE(level >= 0 && level < 30, "accumulateCurve: level out of range");
    if (course.segments() == 0 || region.pixels() == 0) return;
    const double cell = std::ldexp(1.0, level);
    const double localisation = kPointLocalisation * cell;  // min(reach, 4 * 2^i) as for points
    const LevelCourse c = decimate(course, 0.25 * cell);
    const double max_reach = std::min(maxReach(c, profile), localisation);
    if (max_reach <= 0.0) return;

    EnvelopeSmoothing smoothing = envelopeSmoothingForLevel(level, max_reach);
    smoothing.enabled = smooth;
    // Distances are needed a little beyond the reach so the isocurve between inside and outside
    // pixels is interpolated from true values; the grid extends past the region by the smoothing's
    // influence so the mask of region pixels does not depend on where the region ends.
    const double field_px = max_reach + 2.0 * cell;
    const int margin = envelopeInfluencePx(smoothing) + 1;
    auto lo = [&](double v) { return static_cast<int>(std::floor((v - field_px + 0.5) / cell - 0.5)); };
    auto hi = [&](double v) { return static_cast<int>(std::ceil((v + field_px + 0.5) / cell - 0.5)); };
    EnvelopeGrid grid;
    grid.x0 = std::max(region.x - margin, lo(course.min_x));
    grid.y0 = std::max(region.y - margin, lo(course.min_y));
    const int x1 = std::min(region.x + region.width - 1 + margin, hi(course.max_x));
    const int y1 = std::min(region.y + region.height - 1 + margin, hi(course.max_y));
    if (x1 < grid.x0 || y1 < grid.y0) return;
    grid.width = x1 - grid.x0 + 1;
    grid.height = y1 - grid.y0 + 1;

    const ClosestField field = closestField(c, grid, cell, field_px);
    const size_t n = static_cast<size_t>(grid.width) * grid.height;
    grid.f.assign(n, std::numeric_limits<float>::infinity());
    grid.s.assign(n, 0.0);
    for (int gy = 0; gy < grid.height; ++gy)
        for (int gx = 0; gx < grid.width; ++gx) {
            const size_t k = static_cast<size_t>(gy) * grid.width + gx;
            if (field.segment[k] < 0) continue;
            const Attachment a = attach(c, profile, static_cast<size_t>(field.segment[k]), field.u[k], centre(grid.x0 + gx, cell),
                       centre(grid.y0 + gy, cell));
            grid.f[k] = static_cast<float>((std::sqrt(field.dist2[k]) - std::min(a.reach, localisation)) / cell);
            grid.s[k] = a.s;
        }
    const std::vector<uint8_t> inside = envelopeMask(grid, smoothing);

    const int rx0 = std::max(region.x, grid.x0), rx1 = std::min(region.x + region.width - 1, x1);
    const int ry0 = std::max(region.y, grid.y0), ry1 = std::min(region.y + region.height - 1, y1);
    for (int y = ry0; y <= ry1; ++y)
        for (int x = rx0; x <= rx1; ++x) {
            const size_t k = static_cast<size_t>(y - grid.y0) * grid.width + (x - grid.x0);
            if (!inside[k] || field.segment[k] < 0) continue;
            const double qx = centre(x, cell), qy = centre(y, cell);
            const Attachment a = attach(c, profile, static_cast<size_t>(field.segment[k]), field.u[k], qx, qy);
            const double d = std::sqrt(field.dist2[k]);
            const double b = 1.0 / std::max(d, 0.5);
            // Distance across the course the side gradient applies to: on a held free level the
            // two side lines meet in a parabola (C1) instead of a crease.
            const double floor_px = kHeldFloorCells * cell;
            const double across = !held_free_level ? d : (d < floor_px ? 0.5 * d * d / floor_px : d - 0.5 * floor_px);
            const double target = a.height + a.gradient * across * meters_per_pixel0;
            float* out = &sums[3 * (static_cast<size_t>(y - region.y) * region.width + (x - region.x))];
            out[0] += static_cast<float>(b);
            out[1] += static_cast<float>(b * target);
            // phi_d's tolerance is s times the blended distance: widened on a held free level.
            const double tolerance_px = held_free_level ? kHeldCourseToleranceM / kPointToleranceSlope : 0.0;
            out[2] += static_cast<float>(b * (d + tolerance_px));
        }
}

}  // namespace terrasynth::constraints
