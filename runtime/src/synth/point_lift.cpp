// Point heights that hold although the finest levels are free (s5.1 + windowed determinism).
//
// The paper disables geometric constraints on the finest two levels so they do not look intrusive;
// those levels then add their own detail at the site (up to 4% of the relief for a 900 m raise). The
// finished height at a site is a deterministic function of the constraints, and a window of a few
// pixels around the site reproduces it exactly, so the coarse target can be corrected by the
// residual, a few times, until the finished site lands on the asked height. Inside the kernels the
// constraint still acts only through phi_d on the constrained levels.
#include <algorithm>
#include <cmath>
#include <limits>

#include "synth/lift_search.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth {
namespace {

// Slopes gentler than this have no direction worth holding over 7x7 pixels: no tilt lift.
constexpr float kMinTiltedSlopeDeg = 5.0f;
// A site's slope holds when its 7x7 plane's rise is within this fraction of the asked rise (about
// 6 degrees of direction at most).
constexpr float kTiltTolerance = 0.1f;

struct FinishedSite {
    float height = 0.0f;                    // bilinear at the site
    float rise_east = 0.0f, rise_south = 0.0f;  // plane fitted over the 7x7 pixels, metres per metre
};

// The finished site from a window of level 0 around it (equal to the full synthesis): the 2x2
// pixels around the site, or with `plane` its 7x7 pixels and the plane fitted over them.
Result<FinishedSite> finishedSite(Synthesizer& synthesizer, const SynthesisParams& params, const PointConstraint& p,
                                  bool plane) {
    const int64_t cx = std::llround(p.x), cy = std::llround(p.y);
    const PixelWindow window = plane ? PixelWindow{cx - 3, cy - 3, 7, 7}
                                     : PixelWindow{static_cast<int64_t>(std::floor(p.x)), static_cast<int64_t>(std::floor(p.y)), 2, 2};
    auto out = synthesizer.synthesize(window, params, 0, false);
    if (!out) return out.status();
    const Heightfield& h = out->heights;
    FinishedSite site;
    const double fx = std::floor(p.x), fy = std::floor(p.y);
    const int ix = static_cast<int>(static_cast<int64_t>(fx) - window.x), iy = static_cast<int>(static_cast<int64_t>(fy) - window.y);
    const float tx = static_cast<float>(p.x - fx), ty = static_cast<float>(p.y - fy);
    const float top = h.at(ix, iy) + (h.at(ix + 1, iy) - h.at(ix, iy)) * tx;
    const float bottom = h.at(ix, iy + 1) + (h.at(ix + 1, iy + 1) - h.at(ix, iy + 1)) * tx;
    site.height = top + (bottom - top) * ty;
    if (!plane) return site;
    // Least squares over offsets -3..3: sum of dx^2 over the window is 7 * 28.
    double east = 0.0, south = 0.0;
    for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
            east += dx * static_cast<double>(h.at(dx + 3, dy + 3));
            south += dy * static_cast<double>(h.at(dx + 3, dy + 3));
        }
    site.rise_east = static_cast<float>(east / (196.0 * h.meters_per_pixel_x));
    site.rise_south = static_cast<float>(south / (196.0 * h.meters_per_pixel_y));
    return site;
}

// The rise the point asks for, metres per metre east and south.
std::pair<float, float> askedRise(const PointConstraint& p) {
    const double kDegree = 3.14159265358979323846 / 180.0;
    const double rise = std::tan(p.slope_angle_deg * kDegree), direction = p.slope_direction_deg * kDegree;
    return {static_cast<float>(rise * std::sin(direction)), static_cast<float>(-rise * std::cos(direction))};
}

struct PointSearch {
    synth::LiftSearch height, east, south;
    bool tilted = false;
    float lift = 0.0f, tilt_east = 0.0f, tilt_south = 0.0f;  // best round
};

}  // namespace

Result<std::shared_ptr<const SynthesisConstraints>> liftPointConstraints(Synthesizer& synthesizer,
                                                                         const SynthesisParams& params,
                                                                         const PointLiftOptions& options) {
    TERRASYNTH_REQUIRE(options.max_rounds >= 1 && options.tolerance_m >= 0.0f, "liftPointConstraints: bad options");
    if (!params.constraints || params.constraints->points.empty()) return params.constraints;
    auto lifted = std::make_shared<SynthesisConstraints>(*params.constraints);
    std::vector<PointConstraint>& points = lifted->points;
    std::vector<size_t> moving;
    for (size_t i = 0; i < points.size(); ++i) {
        const std::optional<PixelWindow>& w = options.sites_within;
        if (!w || (points[i].x >= w->x && points[i].y >= w->y && points[i].x < w->x + w->width &&
                   points[i].y < w->y + w->height))
            moving.push_back(i);
    }
    SynthesisParams probe = params;
    probe.record_history = false;
    probe.constraints = lifted;
    const double mpp = synthesizer.database().meters_per_pixel;
    std::vector<PointSearch> searches(points.size());
    for (size_t i : moving) {
        // Slopes are held over the site's own pixels only where the free levels hold the site.
        searches[i].tilted = params.hold_on_free_levels && points[i].slope_angle_deg >= kMinTiltedSlopeDeg;
        if (!searches[i].tilted) points[i].tilt_east = points[i].tilt_south = 0.0f;
    }
    float best_worst = std::numeric_limits<float>::infinity();
    for (int round = 0; round < options.max_rounds && !moving.empty(); ++round) {
        // Worst miss in metres: the height at the site, or the plane's error at the 7x7's edge.
        float worst = 0.0f;
        bool held = true;
        for (size_t i : moving) {
            PointConstraint& p = points[i];
            auto site = finishedSite(synthesizer, probe, p, searches[i].tilted);
            if (!site) return site.status().withContext("point constraint " + std::to_string(i));
            const float residual = site->height - p.height_m;
            searches[i].height.record(p.lift_m, residual, round);
            worst = std::max(worst, std::fabs(residual));
            held = held && std::fabs(residual) <= options.tolerance_m;
            if (!searches[i].tilted) continue;
            const auto [east, south] = askedRise(p);
            const float miss_east = site->rise_east - east, miss_south = site->rise_south - south;
            searches[i].east.record(p.tilt_east, miss_east, round);
            searches[i].south.record(p.tilt_south, miss_south, round);
            const float miss = std::hypot(miss_east, miss_south);
            worst = std::max(worst, static_cast<float>(miss * 3.0 * mpp));
            held = held && miss <= kTiltTolerance * std::hypot(east, south);
        }
        // The lifts of a whole round were synthesized together, so the best round is what is kept.
        if (worst < best_worst) {
            best_worst = worst;
            for (size_t i : moving) searches[i].lift = points[i].lift_m, searches[i].tilt_east = points[i].tilt_east,
                                    searches[i].tilt_south = points[i].tilt_south;
        }
        if (held) break;
        for (size_t i : moving) {
            points[i].lift_m = searches[i].height.next();
            if (searches[i].tilted) points[i].tilt_east = searches[i].east.next(), points[i].tilt_south = searches[i].south.next();
        }
    }
    for (size_t i : moving)
        points[i].lift_m = searches[i].lift, points[i].tilt_east = searches[i].tilt_east, points[i].tilt_south = searches[i].tilt_south;
    return std::shared_ptr<const SynthesisConstraints>(std::move(lifted));
}

}  // namespace terrasynth
