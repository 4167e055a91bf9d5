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

// The finished height moves with the lift between steps where a discrete candidate choice flips,
// and other points' lifts shift it a little too (no coherence: s5.3, fig. 7b). The search takes
// secant steps until the residual changes sign, then narrows the bracket by false position
// (bisection when that stalls against one end).
struct LiftSearch {
    struct Sample { float lift = 0.0f, residual = 0.0f; int round = -1; };
    Sample last, previous, opposite;  // opposite: the latest sample on the other side of the target
    // A bracket older than this many rounds is dropped: other points' lifts have moved the site since.
    static constexpr int kBracketRounds = 3;

    void record(float lift, float residual, int round) {
        const Sample now{lift, residual, round};
        if (last.round >= 0 && (residual < 0.0f) != (last.residual < 0.0f)) opposite = last;
        previous = last;
        last = now;
    }
    float next() const {
        if (opposite.round >= 0 && last.round - opposite.round <= kBracketRounds) {
            const float lo = std::min(last.lift, opposite.lift), hi = std::max(last.lift, opposite.lift);
            float lift = last.lift - last.residual * (opposite.lift - last.lift) / (opposite.residual - last.residual);
            if (!(lift > lo + 0.1f * (hi - lo) && lift < hi - 0.1f * (hi - lo))) lift = 0.5f * (lo + hi);
            return lift;
        }
        float slope = 1.0f;  // a lift of the target moves the site about as much
        if (previous.round >= 0 && previous.lift != last.lift) {
            const float measured = (last.residual - previous.residual) / (last.lift - previous.lift);
            if (measured > 0.3f && measured < 3.0f) slope = measured;
        }
        return last.lift - last.residual / slope;
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
    std::vector<float> best_lifts(points.size());
    float best_worst = std::numeric_limits<float>::infinity();
    for (int round = 0; round < options.max_rounds && !moving.empty(); ++round) {
        float worst = 0.0f;
        for (size_t i : moving) {
            auto height = finishedSiteHeight(synthesizer, probe, points[i]);
            if (!height) return height.status().withContext("point constraint " + std::to_string(i));
            const float residual = height.value() - points[i].height_m;
            searches[i].record(points[i].lift_m, residual, round);
            worst = std::max(worst, std::fabs(residual));
        }
        // The lifts of a whole round were synthesized together, so the best round is what is kept.
        if (worst < best_worst) {
            best_worst = worst;
            for (size_t i : moving) best_lifts[i] = points[i].lift_m;
        }
        if (worst <= options.tolerance_m) break;
        for (size_t i : moving) points[i].lift_m = searches[i].next();
    }
    for (size_t i : moving) points[i].lift_m = best_lifts[i];
    return std::shared_ptr<const SynthesisConstraints>(std::move(lifted));
}

}  // namespace terrasynth
