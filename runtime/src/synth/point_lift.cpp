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

#include "synth/synthesis_driver.h"
#include "synth/synthesis_plan.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth {
namespace {

// Sites measured together: one synthesis of `window` (level 0) gives the finished height at every
// site of `points`, bit for bit what a 2x2 window per site gives (windowed determinism).
struct SiteGroup {
    PixelWindow window;
    std::vector<size_t> points;
};

// Windows larger than this are split whatever they would save: their state would take gigabytes.
constexpr int kMaxGroupSide = 2048;

// The 2x2 window around a site: the pixels whose centres (whole coordinates) surround it.
PixelWindow siteWindow(const PointConstraint& p) {
    return {static_cast<int64_t>(std::floor(p.x)), static_cast<int64_t>(std::floor(p.y)), 2, 2};
}

// What synthesizing `w` costs: the pixels of its plan on every level, margins included.
uint64_t planCost(const PixelWindow& w, int coarsest, int passes) {
    const synth::SynthesisPlan plan = synth::planSynthesis(w, 0, coarsest, passes);
    uint64_t pixels = 0;
    for (const synth::LevelRegion& r : plan.regions) pixels += r.pixels();
    return pixels;
}

// Splits the sites at the median of their bounding box's longer side, recursively, and keeps a
// group whole where one window costs no more than its parts (dense sites share their margins and
// coarse levels; scattered ones get small windows). O(n log^2 n).
std::vector<SiteGroup> groupSites(const std::vector<PointConstraint>& points, std::vector<size_t> ids, int coarsest,
                                  int passes, uint64_t* cost) {
    PixelWindow box = siteWindow(points[ids[0]]);
    int64_t x1 = box.x + 1, y1 = box.y + 1;
    for (size_t i : ids) {
        const PixelWindow w = siteWindow(points[i]);
        box.x = std::min(box.x, w.x), box.y = std::min(box.y, w.y);
        x1 = std::max(x1, w.x + 1), y1 = std::max(y1, w.y + 1);
    }
    const bool fits = x1 - box.x < kMaxGroupSide && y1 - box.y < kMaxGroupSide;
    if (fits) {
        box.width = static_cast<int>(x1 - box.x + 1), box.height = static_cast<int>(y1 - box.y + 1);
        *cost = planCost(box, coarsest, passes);
        if (ids.size() == 1 || (box.width == 2 && box.height == 2)) return {SiteGroup{box, std::move(ids)}};
    }
    const bool along_x = x1 - box.x >= y1 - box.y;
    std::sort(ids.begin(), ids.end(), [&](size_t a, size_t b) {
        const double ka = along_x ? points[a].x : points[a].y, kb = along_x ? points[b].x : points[b].y;
        return ka < kb || (ka == kb && a < b);
    });
    const auto middle = ids.begin() + static_cast<long>(ids.size() / 2);
    uint64_t cost_a = 0, cost_b = 0;
    std::vector<SiteGroup> groups = groupSites(points, std::vector<size_t>(ids.begin(), middle), coarsest, passes, &cost_a);
    std::vector<SiteGroup> rest = groupSites(points, std::vector<size_t>(middle, ids.end()), coarsest, passes, &cost_b);
    if (fits && *cost <= cost_a + cost_b) return {SiteGroup{box, std::move(ids)}};
    *cost = cost_a + cost_b;
    groups.insert(groups.end(), std::make_move_iterator(rest.begin()), std::make_move_iterator(rest.end()));
    return groups;
}

// Finished level-0 heights at the (real-valued) sites of `group`: bilinear over the 2x2 pixels
// around each site, whose centres are at whole coordinates.
Status measureSites(Synthesizer& synthesizer, const SynthesisParams& params, const std::vector<PointConstraint>& points,
                    const SiteGroup& group, std::vector<float>& heights) {
    auto out = synthesizer.synthesize(group.window, params, 0, false);
    if (!out) return out.status().withContext("point constraint " + std::to_string(group.points.front()));
    const Heightfield& h = out->heights;
    for (size_t i : group.points) {
        const PointConstraint& p = points[i];
        const double fx = std::floor(p.x), fy = std::floor(p.y);
        const int x = static_cast<int>(static_cast<int64_t>(fx) - group.window.x);
        const int y = static_cast<int>(static_cast<int64_t>(fy) - group.window.y);
        const float tx = static_cast<float>(p.x - fx), ty = static_cast<float>(p.y - fy);
        const float top = h.at(x, y) + (h.at(x + 1, y) - h.at(x, y)) * tx;
        const float bottom = h.at(x, y + 1) + (h.at(x + 1, y + 1) - h.at(x, y + 1)) * tx;
        heights[i] = top + (bottom - top) * ty;
    }
    return Status::ok();
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
    // Validated once here, so the grouping below only ever sees sites synthesis accepts.
    if (Status s = synth::validateRequest(synthesizer.database(), PixelWindow{0, 0, 1, 1}, probe, 0); !s) return s;
    std::vector<SiteGroup> groups;
    if (!moving.empty()) {
        uint64_t cost = 0;
        groups = groupSites(points, moving, synth::coarsestLevel(synthesizer.database(), probe), probe.correction_passes, &cost);
    }
    std::vector<LiftSearch> searches(points.size());
    std::vector<float> best_lifts(points.size()), heights(points.size());
    float best_worst = std::numeric_limits<float>::infinity();
    for (int round = 0; round < options.max_rounds && !moving.empty(); ++round) {
        for (const SiteGroup& group : groups)
            if (Status s = measureSites(synthesizer, probe, points, group, heights); !s) return s;
        float worst = 0.0f;
        for (size_t i : moving) {
            const float residual = heights[i] - points[i].height_m;
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
