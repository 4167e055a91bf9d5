// Plane geometry of the sketching tools (terrasynth_editor/sketch_geometry.h).
#include "terrasynth_editor/sketch_geometry.h"

#include <algorithm>
#include <cmath>

namespace terrasynth::editor {
namespace {

double dist(const std::pair<double, double>& a, const std::pair<double, double>& b) {
    return std::hypot(a.first - b.first, a.second - b.second);
}

// Intersection of segments p0-p1 and q0-q1 (proper or touching), if any.
std::optional<std::pair<double, double>> segmentCrossing(const std::pair<double, double>& p0,
                                                         const std::pair<double, double>& p1,
                                                         const std::pair<double, double>& q0,
                                                         const std::pair<double, double>& q1) {
    const double rx = p1.first - p0.first, ry = p1.second - p0.second;
    const double sx = q1.first - q0.first, sy = q1.second - q0.second;
    const double denom = rx * sy - ry * sx;
    if (std::fabs(denom) < 1e-12) return std::nullopt;
    const double qpx = q0.first - p0.first, qpy = q0.second - p0.second;
    const double t = (qpx * sy - qpy * sx) / denom, u = (qpx * ry - qpy * rx) / denom;
    if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0) return std::nullopt;
    return std::make_pair(p0.first + t * rx, p0.second + t * ry);
}

}  // namespace

Polyline decimate(const Polyline& line, double spacing) {
    if (line.size() <= 2) return line;
    Polyline out{line.front()};
    for (size_t i = 1; i + 1 < line.size(); ++i)
        if (dist(line[i], out.back()) >= spacing) out.push_back(line[i]);
    // The last point replaces a kept point too close to it.
    if (out.size() > 1 && dist(line.back(), out.back()) < 0.5 * spacing) out.pop_back();
    out.push_back(line.back());
    return out;
}

double polylineLength(const Polyline& line) {
    double length = 0.0;
    for (size_t i = 1; i < line.size(); ++i) length += dist(line[i - 1], line[i]);
    return length;
}

std::pair<double, double> pointAtFraction(const Polyline& line, double t) {
    if (line.empty()) return {0.0, 0.0};
    const double target = std::clamp(t, 0.0, 1.0) * polylineLength(line);
    double walked = 0.0;
    for (size_t i = 1; i < line.size(); ++i) {
        const double d = dist(line[i - 1], line[i]);
        if (walked + d >= target && d > 0.0) {
            const double f = (target - walked) / d;
            return {line[i - 1].first + f * (line[i].first - line[i - 1].first),
                    line[i - 1].second + f * (line[i].second - line[i - 1].second)};
        }
        walked += d;
    }
    return line.back();
}

Nearest nearestOnPolyline(const Polyline& line, double x, double y) {
    Nearest best;
    best.distance = line.empty() ? 0.0 : dist(line.front(), {x, y});
    const double total = polylineLength(line);
    double walked = 0.0;
    for (size_t i = 1; i < line.size(); ++i) {
        const auto& a = line[i - 1];
        const auto& b = line[i];
        const double dx = b.first - a.first, dy = b.second - a.second;
        const double len2 = dx * dx + dy * dy;
        const double f = len2 > 0.0 ? std::clamp(((x - a.first) * dx + (y - a.second) * dy) / len2, 0.0, 1.0) : 0.0;
        const double d = std::hypot(a.first + f * dx - x, a.second + f * dy - y);
        const double len = std::sqrt(len2);
        if (d < best.distance || (i == 1 && d <= best.distance)) {
            best.distance = d;
            best.segment = static_cast<int>(i - 1);
            best.t = total > 0.0 ? (walked + f * len) / total : 0.0;
        }
        walked += len;
    }
    return best;
}

Polyline overSketch(const Polyline& course, const Polyline& stroke) {
    if (course.size() < 2 || stroke.size() < 2) return course;
    Nearest start = nearestOnPolyline(course, stroke.front().first, stroke.front().second);
    Nearest end = nearestOnPolyline(course, stroke.back().first, stroke.back().second);
    Polyline s = stroke;
    if (end.t < start.t) {
        std::reverse(s.begin(), s.end());
        std::swap(start, end);
    }
    // Keep the course before the stroke's first point and after its last one.
    Polyline out(course.begin(), course.begin() + start.segment + 1);
    if (start.t <= 0.0) out.clear();
    out.insert(out.end(), s.begin(), s.end());
    if (end.t < 1.0) out.insert(out.end(), course.begin() + end.segment + 1, course.end());
    // Drop repeated points so every segment has a direction.
    Polyline clean;
    for (const auto& p : out)
        if (clean.empty() || dist(clean.back(), p) > 1e-9) clean.push_back(p);
    return clean.size() >= 2 ? clean : course;
}

std::vector<std::pair<double, double>> crossings(const Polyline& a, const Polyline& b) {
    std::vector<std::pair<double, double>> out;
    for (size_t i = 1; i < a.size(); ++i)
        for (size_t j = 1; j < b.size(); ++j)
            if (auto c = segmentCrossing(a[i - 1], a[i], b[j - 1], b[j])) out.push_back(*c);
    return out;
}

std::vector<std::pair<double, double>> selfCrossings(const Polyline& a) {
    std::vector<std::pair<double, double>> out;
    for (size_t i = 1; i < a.size(); ++i)
        for (size_t j = i + 2; j < a.size(); ++j)
            if (auto c = segmentCrossing(a[i - 1], a[i], a[j - 1], a[j])) out.push_back(*c);
    return out;
}

std::pair<double, double> centroid(const Polyline& p) {
    double area = 0.0, cx = 0.0, cy = 0.0;
    for (size_t i = 0; i < p.size(); ++i) {
        const auto& a = p[i];
        const auto& b = p[(i + 1) % p.size()];
        const double cross = a.first * b.second - b.first * a.second;
        area += cross;
        cx += (a.first + b.first) * cross;
        cy += (a.second + b.second) * cross;
    }
    if (std::fabs(area) < 1e-9) {
        double mx = 0.0, my = 0.0;
        for (const auto& q : p) mx += q.first, my += q.second;
        const double n = p.empty() ? 1.0 : static_cast<double>(p.size());
        return {mx / n, my / n};
    }
    return {cx / (3.0 * area), cy / (3.0 * area)};
}

bool insidePolygon(const Polyline& p, double x, double y) {
    bool inside = false;
    if (p.size() < 3) return false;
    for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
        const auto& a = p[i];
        const auto& b = p[j];
        if ((a.second > y) != (b.second > y) && x < (b.first - a.first) * (y - a.second) / (b.second - a.second) + a.first)
            inside = !inside;
    }
    return inside;
}

}  // namespace terrasynth::editor
