// Private: the course of a curve constraint (Gain et al. 2015 s3, s5.1) as a dense polyline with arc
// lengths, and closest-point queries on it. Implemented in curve_geometry.cpp.
#pragma once

#include <memory>
#include <vector>

#include "terrasynth/constraints.h"

namespace terrasynth::constraints {

// The course sampled finely enough that every segment is straight to well under a level-0 pixel:
// a centripetal Catmull-Rom spline through the course points (no cusps or self-loops between close
// points) or the polyline itself, subdivided so no segment is longer than kMaxSegmentPx.
struct CourseSamples {
    std::vector<double> x, y;  // level-0 global pixels
    std::vector<double> s;     // arc length from the start, level-0 pixels; s.front() = 0
    double length = 0.0;       // s.back(); > 0 for a usable course
    bool closed = false;       // first and last course point coincide: no end caps
    double min_x = 0, min_y = 0, max_x = 0, max_y = 0;

    size_t segments() const { return x.size() < 2 ? 0 : x.size() - 1; }
};

constexpr double kMaxSegmentPx = 1.0;

// Samples a course. Consecutive duplicate points are dropped; a course with fewer than two distinct
// points gives an empty sampling (segments() == 0), which the rasteriser skips.
CourseSamples sampleCourse(const std::vector<std::pair<double, double>>& course, bool spline);

// The same, cached by the course points and spline flag so the sampling (and everything derived from
// the course alone) is recomputed only when the horizontal shape changes (s5.1). Thread-safe; the
// cache keeps the most recently used courses and drops the oldest beyond a small bound.
std::shared_ptr<const CourseSamples> cachedCourse(const CurveConstraint& curve);

// Closest point of segment i (samples i -> i+1) to (px, py): u in [0, 1] along the segment and the
// squared distance.
struct SegmentHit {
    double u = 0.0;
    double dist2 = 0.0;
};
inline SegmentHit closestOnSegment(const CourseSamples& c, size_t i, double px, double py) {
    const double ax = c.x[i], ay = c.y[i];
    const double ex = c.x[i + 1] - ax, ey = c.y[i + 1] - ay;
    const double len2 = ex * ex + ey * ey;
    double u = len2 > 0.0 ? ((px - ax) * ex + (py - ay) * ey) / len2 : 0.0;
    u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    const double dx = px - (ax + u * ex), dy = py - (ay + u * ey);
    return {u, dx * dx + dy * dy};
}

}  // namespace terrasynth::constraints
