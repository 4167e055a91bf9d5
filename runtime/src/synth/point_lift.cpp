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

#include "terrasynth/synthesizer.h"

namespace terrasynth {
namespace {

// Finished level-0 height at the (real-valued) site: bilinear over the 2x2 pixels around it, whose
// centres are at whole coordinates.
Result<float> finishedSiteHeight(Synthesizer& synthesizer, const SynthesisParams& params, const PointConstraint& p) {
    const double fx = std::floor(p.x), fy = std::floor(p.y);
    const PixelWindow window{static_cast<int64_t>(fx), static_cast<int64_t>(fy), 2, 2};
    auto out = synthesizer.synthesize(window, params, 0, false);
    if (!out) return out.status();
    const Heightfield& h = out->heights;
    const float tx = static_cast<float>(p.x - fx), ty = static_cast<float>(p.y - fy);
    const float top = h.at(0, 0) + (h.at(1, 0) - h.at(0, 0)) * tx;
    const float bottom = h.at(0, 1) + (h.at(1, 1) - h.at(0, 1)) * tx;
    return top + (bottom - top) * ty;
}

// The finished height is a step function of the lift where a discrete candidate choice flips,
// and close to "lift + constant" between steps. So the search steps by the residual until the
// residual changes sign, then narrows the bracket by false position (bisection when that stalls).
struct LiftSearch {
    float best_lift = 0.0f, best_residual = std::numeric_limits<float>::infinity();
    float last_lift = 0.0f, last_residual = 0.0f;
    bool has_below = false, has_above = false;  // a lift whose site lands below / above the target
    float below_lift = 0.0f, below_residual = 0.0f, above_lift = 0.0f, above_residual = 0.0f;

    void record(float lift, float residual) {
        last_lift = lift, last_residual = residual;
        if (std::fabs(residual) < std::fabs(best_residual)) best_lift = lift, best_residual = residual;
        if (residual < 0.0f) has_below = true, below_lift = lift, below_residual = residual;
        if (residual > 0.0f) has_above = true, above_lift = lift, above_residual = residual;
    }
    float next() const {
        if (!(has_below && has_above)) return last_lift - last_residual;
        const float span = above_lift - below_lift;
        float lift = below_lift - below_residual * span / (above_residual - below_residual);
        // Keep away from the ends so a step between them is found in a few rounds.
        const float lo = std::min(below_lift, above_lift), hi = std::max(below_lift, above_lift);
        if (!(lift > lo + 0.1f * (hi - lo) && lift < hi - 0.1f * (hi - lo))) lift = 0.5f * (below_lift + above_lift);
        return lift;
    }
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
    std::vector<LiftSearch> searches(points.size());
    for (int round = 0; round < options.max_rounds && !moving.empty(); ++round) {
        bool all_within = true;
        for (size_t i : moving) {
            auto height = finishedSiteHeight(synthesizer, probe, points[i]);
            if (!height) return height.status().withContext("point constraint " + std::to_string(i));
            const float residual = height.value() - points[i].height_m;
            searches[i].record(points[i].lift_m, residual);
            all_within = all_within && std::fabs(residual) <= options.tolerance_m;
        }
        if (all_within) break;
        // Overlapping points move each other's sites a little; each keeps searching its own lift.
        for (size_t i : moving) points[i].lift_m = searches[i].next();
    }
    for (size_t i : moving) points[i].lift_m = searches[i].best_lift;
    return std::shared_ptr<const SynthesisConstraints>(std::move(lifted));
}

}  // namespace terrasynth
