// Course sampling for curve constraints (Gain et al. 2015 s3: "an initial course is laid out by
// sketching"; s5.1: closest-point queries on it).
#include "constraints/curve_geometry.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <utility>

#include "terrasynth/limits.h"

namespace terrasynth::constraints {
namespace {

struct Point {
    double x, y;
};

double distance(Point a, Point b) { return std::hypot(b.x - a.x, b.y - a.y); }

std::vector<Point> distinctPoints(const std::vector<std::pair<double, double>>& course) {
    std::vector<Point> points;
    for (const auto& [x, y] : course)
        if (points.empty() || distance(points.back(), {x, y}) > 1e-9) points.push_back({x, y});
    return points;
}

Point lerp(Point a, Point b, double ta, double tb, double t) {
    const double w = (t - ta) / (tb - ta);
    return {a.x + (b.x - a.x) * w, a.y + (b.y - a.y) * w};
}

// Centripetal Catmull-Rom span p1 -> p2 (Barry-Goldman pyramid): knot spacing |dp|^0.5 keeps the
// spline from overshooting into cusps or loops where course points are unevenly spaced.
Point catmullRom(Point p0, Point p1, Point p2, Point p3, double f) {
    const double t0 = 0.0;
    const double t1 = t0 + std::sqrt(distance(p0, p1));
    const double t2 = t1 + std::sqrt(distance(p1, p2));
    const double t3 = t2 + std::sqrt(distance(p2, p3));
    const double t = t1 + (t2 - t1) * f;
    const Point a1 = lerp(p0, p1, t0, t1, t), a2 = lerp(p1, p2, t1, t2, t), a3 = lerp(p2, p3, t2, t3, t);
    const Point b1 = lerp(a1, a2, t0, t2, t), b2 = lerp(a2, a3, t1, t3, t);
    return lerp(b1, b2, t1, t2, t);
}

std::vector<Point> splineSamples(const std::vector<Point>& p, bool closed) {
    const size_t n = p.size();
    // Open ends get reflected phantom neighbours so the end tangent follows the first/last span.
    auto at = [&](long i) -> Point {
        if (closed) return p[static_cast<size_t>((i % long(n - 1) + long(n - 1)) % long(n - 1))];
        if (i < 0) return {2 * p[0].x - p[1].x, 2 * p[0].y - p[1].y};
        if (i >= long(n)) return {2 * p[n - 1].x - p[n - 2].x, 2 * p[n - 1].y - p[n - 2].y};
        return p[static_cast<size_t>(i)];
    };
    std::vector<Point> out{p[0]};
    for (long i = 0; i + 1 < long(n); ++i) {
        const Point p0 = at(i - 1), p1 = at(i), p2 = at(i + 1), p3 = at(i + 2);
        // A span is at most ~1.5x its chord for centripetal splines; sample densely enough.
        const int steps = std::max(2, static_cast<int>(std::ceil(1.5 * distance(p1, p2) / kMaxSegmentPx)));
        for (int k = 1; k <= steps; ++k) out.push_back(k == steps ? p2 : catmullRom(p0, p1, p2, p3, double(k) / steps));
    }
    return out;
}

std::vector<Point> polylineSamples(const std::vector<Point>& p) {
    std::vector<Point> out{p[0]};
    for (size_t i = 0; i + 1 < p.size(); ++i) {
        const int steps = std::max(1, static_cast<int>(std::ceil(distance(p[i], p[i + 1]) / kMaxSegmentPx)));
        for (int k = 1; k <= steps; ++k) out.push_back(lerp(p[i], p[i + 1], 0.0, 1.0, double(k) / steps));
    }
    return out;
}

}  // namespace

CourseSamples sampleCourse(const std::vector<std::pair<double, double>>& course, bool spline) {
    CourseSamples c;
    const std::vector<Point> points = distinctPoints(course);
    if (points.size() < 2) return c;
    c.closed = points.size() >= 4 && distance(points.front(), points.back()) < 1e-6;
    const std::vector<Point> samples = spline && points.size() >= 3 ? splineSamples(points, c.closed) : polylineSamples(points);
    c.min_x = c.max_x = samples[0].x;
    c.min_y = c.max_y = samples[0].y;
    double s = 0.0;
    for (size_t i = 0; i < samples.size(); ++i) {
        if (i > 0) {
            const double step = distance(samples[i - 1], samples[i]);
            if (step < 1e-9) continue;  // zero-length segments carry no direction
            s += step;
        }
        c.x.push_back(samples[i].x);
        c.y.push_back(samples[i].y);
        c.s.push_back(s);
        c.min_x = std::min(c.min_x, samples[i].x);
        c.max_x = std::max(c.max_x, samples[i].x);
        c.min_y = std::min(c.min_y, samples[i].y);
        c.max_y = std::max(c.max_y, samples[i].y);
    }
    c.length = s;
    if (c.x.size() < 2) c = CourseSamples{};
    return c;
}

std::shared_ptr<const CourseSamples> cachedCourse(const CurveConstraint& curve) {
    struct Entry {
        std::vector<std::pair<double, double>> course;
        bool spline;
        std::shared_ptr<const CourseSamples> samples;
    };
    // Room for one project at the limits (kMaxCurves courses, about 1.5 samples per pixel of course
    // length), and no more than that in memory whatever was cached before.
    constexpr size_t kCapacity = static_cast<size_t>(limits::kMaxCurves);
    constexpr size_t kMaxSamples = 4 * static_cast<size_t>(limits::kMaxTotalCourseLengthPx);
    static std::mutex mutex;
    static std::vector<Entry> entries;  // most recently used first
    {
        std::lock_guard<std::mutex> lock(mutex);
        for (size_t i = 0; i < entries.size(); ++i) {
            if (entries[i].spline != curve.spline || entries[i].course != curve.course) continue;
            std::rotate(entries.begin(), entries.begin() + static_cast<long>(i), entries.begin() + static_cast<long>(i) + 1);
            return entries.front().samples;
        }
    }
    auto samples = std::make_shared<const CourseSamples>(sampleCourse(curve.course, curve.spline));
    std::lock_guard<std::mutex> lock(mutex);
    entries.insert(entries.begin(), Entry{curve.course, curve.spline, samples});
    size_t total = 0;
    for (const Entry& e : entries) total += e.samples->x.size();
    while (entries.size() > 1 && (entries.size() > kCapacity || total > kMaxSamples)) {
        total -= entries.back().samples->x.size();
        entries.pop_back();
    }
    return samples;
}

}  // namespace terrasynth::constraints
