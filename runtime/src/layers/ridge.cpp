// Ridges of s4.2: a sketched ridge line with a sketched crest-height profile and a Gaussian
// cross-section (as in Belhadj & Audibert 2005, which the paper cites for ridge shapes).
#include <algorithm>
#include <cmath>
#include <string>

#include "layers/parallel.h"
#include "terrasynth/layers_tools.h"
#include "terrasynth/limits.h"

namespace terrasynth {
namespace {

struct Segment {
    double ax, ay, dx, dy, len2, s0, len;
    int x0, x1, y0, y1;  // pixel bounds of its influence
};

double crestAt(const RidgeParams& p, double s, double total) {
    const auto& prof = p.profile_m;
    if (prof.size() == 1 || total <= 0) return prof.front();
    const double pos = std::clamp(s / total, 0.0, 1.0) * (prof.size() - 1);
    const size_t i = std::min(static_cast<size_t>(pos), prof.size() - 2);
    const double t = pos - i;
    return prof[i] * (1.0 - t) + prof[i + 1] * t;
}

}  // namespace

Status validateRidge(const RidgeParams& p) {
    if (p.points.size() < 2 || p.points.size() > static_cast<size_t>(limits::kMaxRidgePoints))
        return Status::error("points: a ridge needs 2.." + std::to_string(limits::kMaxRidgePoints) + " points");
    if (p.profile_m.size() > 100000) return Status::error("profile_m: at most 100000 heights");
    for (size_t i = 0; i < p.points.size(); ++i)
        if (!std::isfinite(p.points[i][0]) || !std::isfinite(p.points[i][1]) || std::fabs(p.points[i][0]) > 1e6 ||
            std::fabs(p.points[i][1]) > 1e6)
            return Status::error("points[" + std::to_string(i) + "]: must be finite pixel coordinates");
    if (p.profile_m.empty()) return Status::error("profile_m: needs at least one height");
    for (size_t i = 0; i < p.profile_m.size(); ++i)
        if (!std::isfinite(p.profile_m[i]) || std::fabs(p.profile_m[i]) > 1e4)
            return Status::error("profile_m[" + std::to_string(i) + "]: must be finite with |h| <= 10000");
    if (!(p.width_px > 0.0 && p.width_px <= 1e4)) return Status::error("width_px: must be > 0");
    return Status::ok();
}

namespace {

// The segments with their pixel bounds (reach clipped to the grid).
std::vector<Segment> ridgeSegments(const RidgeParams& p, int width, int height, double* total_length) {
    // Beyond this distance the cross-section is below 1e-6 of the crest.
    const double reach = p.width_px * std::sqrt(2.0 * std::log(1.0e6));
    std::vector<Segment> segs;
    double s = 0.0;
    for (size_t i = 0; i + 1 < p.points.size(); ++i) {
        Segment g;
        g.ax = p.points[i][0];
        g.ay = p.points[i][1];
        g.dx = p.points[i + 1][0] - g.ax;
        g.dy = p.points[i + 1][1] - g.ay;
        g.len2 = g.dx * g.dx + g.dy * g.dy;
        g.len = std::sqrt(g.len2);
        g.s0 = s;
        s += g.len;
        g.x0 = std::max(0, static_cast<int>(std::floor(std::min(g.ax, g.ax + g.dx) - reach)));
        g.x1 = std::min(width, static_cast<int>(std::ceil(std::max(g.ax, g.ax + g.dx) + reach)) + 1);
        g.y0 = std::max(0, static_cast<int>(std::floor(std::min(g.ay, g.ay + g.dy) - reach)));
        g.y1 = std::min(height, static_cast<int>(std::ceil(std::max(g.ay, g.ay + g.dy) + reach)) + 1);
        segs.push_back(g);
    }
    *total_length = s;
    return segs;
}

}  // namespace

uint64_t ridgeReliefCost(const RidgeParams& p, int width, int height) {
    double total = 0.0;
    uint64_t cost = static_cast<uint64_t>(std::max(0, width)) * std::max(0, height);
    for (const Segment& g : ridgeSegments(p, width, height, &total))
        cost += static_cast<uint64_t>(std::max(0, g.x1 - g.x0)) * std::max(0, g.y1 - g.y0);
    return cost;
}

Heightfield ridgeRelief(const RidgeParams& p, int width, int height, double meters_per_pixel) {
    TERRASYNTH_REQUIRE(validateRidge(p).isOk(), "invalid ridge");
    Heightfield out(width, height, meters_per_pixel);
    const double reach = p.width_px * std::sqrt(2.0 * std::log(1.0e6));
    double total = 0.0;
    const std::vector<Segment> segs = ridgeSegments(p, width, height, &total);
    const double inv2w2 = 1.0 / (2.0 * p.width_px * p.width_px);
    layers::parallelFor(height, 8L * width, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (const Segment& g : segs) {
                if (y < g.y0 || y >= g.y1) continue;
                for (int x = g.x0; x < g.x1; ++x) {
                    const double px = x - g.ax, py = y - g.ay;
                    const double t = g.len2 > 0 ? std::clamp((px * g.dx + py * g.dy) / g.len2, 0.0, 1.0) : 0.0;
                    const double ex = px - t * g.dx, ey = py - t * g.dy;
                    const double d2 = ex * ex + ey * ey;
                    if (d2 > reach * reach) continue;
                    const double h = crestAt(p, g.s0 + t * g.len, total) * std::exp(-d2 * inv2w2);
                    float& o = out.at(x, y);
                    // Overlapping segments (bends, crossings) keep the stronger contribution.
                    if (std::fabs(h) > std::fabs(o)) o = static_cast<float>(h);
                }
            }
    });
    return out;
}

}  // namespace terrasynth
