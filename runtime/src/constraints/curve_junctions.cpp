// Junction widgets at curve crossings (Gain et al. 2015 s3, Figure 2c).
#include "constraints/curve_junctions.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <unordered_map>

namespace terrasynth::constraints {
namespace {

constexpr double kCellPx = 16.0;

struct SegmentRef {
    size_t course, segment;
};

// Proper or touching intersection of p0->p1 and q0->q1: parameters along each.
bool intersect(double p0x, double p0y, double p1x, double p1y, double q0x, double q0y, double q1x, double q1y,
               double* u, double* v) {
    const double rx = p1x - p0x, ry = p1y - p0y, sx = q1x - q0x, sy = q1y - q0y;
    const double denom = rx * sy - ry * sx;
    if (std::abs(denom) < 1e-12) return false;  // parallel: overlapping courses have no single junction
    const double qpx = q0x - p0x, qpy = q0y - p0y;
    *u = (qpx * sy - qpy * sx) / denom;
    *v = (qpx * ry - qpy * rx) / denom;
    return *u >= 0.0 && *u <= 1.0 && *v >= 0.0 && *v <= 1.0;
}

bool adjacent(const CourseSamples& c, size_t i, size_t j) {
    if (i > j) std::swap(i, j);
    return j - i <= 1 || (c.closed && i == 0 && j + 1 == c.segments());
}

}  // namespace

CrossingSearch findCrossings(const std::vector<const CourseSamples*>& courses) {
    CrossingSearch result;
    std::unordered_map<int64_t, std::vector<SegmentRef>> cells;
    // Shifted as unsigned: cells left of or above the origin have negative indices (a left shift of
    // a negative value is undefined; found by fuzzing).
    auto key = [](int64_t cx, int64_t cy) {
        return static_cast<int64_t>((static_cast<uint64_t>(cx) << 32) ^ (static_cast<uint64_t>(cy) & 0xffffffffu));
    };
    for (size_t k = 0; k < courses.size(); ++k) {
        const CourseSamples& c = *courses[k];
        for (size_t i = 0; i < c.segments(); ++i) {
            const int64_t x0 = static_cast<int64_t>(std::floor(std::min(c.x[i], c.x[i + 1]) / kCellPx));
            const int64_t x1 = static_cast<int64_t>(std::floor(std::max(c.x[i], c.x[i + 1]) / kCellPx));
            const int64_t y0 = static_cast<int64_t>(std::floor(std::min(c.y[i], c.y[i + 1]) / kCellPx));
            const int64_t y1 = static_cast<int64_t>(std::floor(std::max(c.y[i], c.y[i + 1]) / kCellPx));
            for (int64_t cy = y0; cy <= y1; ++cy)
                for (int64_t cx = x0; cx <= x1; ++cx) cells[key(cx, cy)].push_back({k, i});
        }
    }
    // The pairs to test, counted before testing any: a scribble piles thousands of segments into
    // one cell.
    uint64_t pair_tests = 0;
    for (const auto& entry : cells) pair_tests += uint64_t(entry.second.size()) * (entry.second.size() - 1) / 2;
    if (pair_tests > kMaxCrossingTests) {
        result.complete = false;
        return result;
    }
    // A crossing is seen from every cell both segments share (up to 4 for a crossing on a corner).
    const size_t max_found = 8 * static_cast<size_t>(limits::kMaxJunctions);
    std::vector<CourseCrossing> found;
    for (const auto& [cell, refs] : cells) {
        (void)cell;
        if (found.size() > max_found) break;
        for (size_t m = 0; m < refs.size(); ++m)
            for (size_t n = m + 1; n < refs.size(); ++n) {
                SegmentRef p = refs[m], q = refs[n];
                if (p.course > q.course || (p.course == q.course && p.segment > q.segment)) std::swap(p, q);
                const CourseSamples& a = *courses[p.course];
                const CourseSamples& b = *courses[q.course];
                if (p.course == q.course && adjacent(a, p.segment, q.segment)) continue;
                double u, v;
                if (!intersect(a.x[p.segment], a.y[p.segment], a.x[p.segment + 1], a.y[p.segment + 1], b.x[q.segment],
                               b.y[q.segment], b.x[q.segment + 1], b.y[q.segment + 1], &u, &v))
                    continue;
                CourseCrossing x;
                x.a = p.course;
                x.b = q.course;
                x.s_a = a.s[p.segment] + u * (a.s[p.segment + 1] - a.s[p.segment]);
                x.s_b = b.s[q.segment] + v * (b.s[q.segment + 1] - b.s[q.segment]);
                x.x = a.x[p.segment] + u * (a.x[p.segment + 1] - a.x[p.segment]);
                x.y = a.y[p.segment] + u * (a.y[p.segment + 1] - a.y[p.segment]);
                found.push_back(x);
            }
    }
    // Hash-map order is not deterministic: sort, then drop repeats (a crossing seen from several
    // cells, or at a sample shared by two segments).
    std::sort(found.begin(), found.end(), [](const CourseCrossing& l, const CourseCrossing& r) {
        return std::tie(l.a, l.b, l.s_a, l.s_b) < std::tie(r.a, r.b, r.s_a, r.s_b);
    });
    // `unique` stays sorted like `found`, so the earlier crossings within 1 pixel of arc length on
    // course a are a run at its end: scan back through that run only.
    std::vector<CourseCrossing>& unique = result.crossings;
    for (const CourseCrossing& x : found) {
        bool repeat = false;
        for (auto u = unique.rbegin(); u != unique.rend() && u->a == x.a && u->b == x.b && x.s_a - u->s_a < 1.0; ++u)
            if (std::abs(u->s_a - x.s_a) < 1.0 && std::abs(u->s_b - x.s_b) < 1.0) {
                repeat = true;
                break;
            }
        if (!repeat) unique.push_back(x);
    }
    if (found.size() > max_found || unique.size() > static_cast<size_t>(limits::kMaxJunctions)) result.complete = false;
    return result;
}

void pinJunctions(const std::vector<CourseCrossing>& crossings, std::vector<CurveProfile>& profiles) {
    // Pins depend on the widgets only, never on each other: collect them, then index each profile's
    // once (thousands of junctions must not cost an insertion each).
    std::vector<std::vector<JunctionPin>> pins(profiles.size());
    for (const CourseCrossing& x : crossings) {
        const CurveProfile& a = profiles[x.a];
        const CurveProfile& b = profiles[x.b];
        double ha = 0.0, hb = 0.0;
        const bool wa = a.widgetNear(x.s_a, kJunctionWidgetSnapPx, &ha);
        const bool wb = b.widgetNear(x.s_b, kJunctionWidgetSnapPx, &hb);
        double height;
        if (wa && wb) height = 0.5 * (ha + hb);
        else if (wa) height = ha;
        else if (wb) height = hb;
        else height = 0.5 * (a.heightAt(x.s_a) + b.heightAt(x.s_b));
        const CurveProperties pa = a.widgetsAt(a.t(x.s_a)), pb = b.widgetsAt(b.t(x.s_b));
        const double blend = std::max({4.0, pa.left_reach, pa.right_reach, pb.left_reach, pb.right_reach});
        pins[x.a].push_back({x.s_a, height, blend});
        pins[x.b].push_back({x.s_b, height, blend});
    }
    for (size_t k = 0; k < profiles.size(); ++k)
        if (!pins[k].empty()) profiles[k].setPins(std::move(pins[k]));
}

}  // namespace terrasynth::constraints
