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
#include <tuple>

#include "synth/lift_search.h"
#include "synth/synthesis_driver.h"
#include "synth/synthesis_plan.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth {
namespace {

// Slopes gentler than this have no direction worth holding over 7x7 pixels: no tilt lift.
constexpr float kMinTiltedSlopeDeg = 5.0f;
// A site's slope holds when its 7x7 plane's rise is within this fraction of the asked rise (about
// 6 degrees of direction at most).
constexpr float kTiltTolerance = 0.1f;

// Sites measured together: one synthesis of `window` (level 0) gives the finished height at every
// site of `points`, bit for bit what a 2x2 window per site gives (windowed determinism).
struct SiteGroup {
    PixelWindow window;
    std::vector<size_t> points;
};

// Windows larger than this are split whatever they would save: their state would take gigabytes.
constexpr int kMaxGroupSide = 2048;

// Half the side of the square a tilted site's wide plane is fitted over: half its radius (at least
// its 7x7 pixels, at most what one group's window holds).
int wideHalf(const PointConstraint& p) {
    return static_cast<int>(std::clamp(p.radius_px / 2.0f, 3.0f, static_cast<float>(kMaxGroupSide / 2 - 1)));
}

// What a site's slope is measured on: nothing, the plane over its 7x7 pixels, or that and the
// plane over the square of wideHalf.
enum class SitePlane : uint8_t { None, Own, Wide };

// The pixels a site is measured on: the 2x2 whose centres (whole coordinates) surround it, or the
// 7x7 or wideHalf square around its nearest pixel (which hold those 2x2).
PixelWindow siteWindow(const PointConstraint& p, SitePlane plane) {
    if (plane == SitePlane::None) return {static_cast<int64_t>(std::floor(p.x)), static_cast<int64_t>(std::floor(p.y)), 2, 2};
    const int half = plane == SitePlane::Wide ? wideHalf(p) : 3;
    return {std::llround(p.x) - half, std::llround(p.y) - half, 2 * half + 1, 2 * half + 1};
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
std::vector<SiteGroup> groupSites(const std::vector<PointConstraint>& points, const std::vector<PixelWindow>& sites,
                                  std::vector<size_t> ids, int coarsest, int passes, uint64_t* cost) {
    PixelWindow box = sites[ids[0]];
    int64_t x1 = box.x + box.width - 1, y1 = box.y + box.height - 1;
    for (size_t i : ids) {
        const PixelWindow& w = sites[i];
        box.x = std::min(box.x, w.x), box.y = std::min(box.y, w.y);
        x1 = std::max(x1, w.x + w.width - 1), y1 = std::max(y1, w.y + w.height - 1);
    }
    const bool fits = x1 - box.x < kMaxGroupSide && y1 - box.y < kMaxGroupSide;
    if (fits) {
        box.width = static_cast<int>(x1 - box.x + 1), box.height = static_cast<int>(y1 - box.y + 1);
        *cost = planCost(box, coarsest, passes);
        if (ids.size() == 1 || (box.width == sites[ids[0]].width && box.height == sites[ids[0]].height)) return {SiteGroup{box, std::move(ids)}};
    }
    const bool along_x = x1 - box.x >= y1 - box.y;
    std::sort(ids.begin(), ids.end(), [&](size_t a, size_t b) {
        const double ka = along_x ? points[a].x : points[a].y, kb = along_x ? points[b].x : points[b].y;
        return ka < kb || (ka == kb && a < b);
    });
    const auto middle = ids.begin() + static_cast<long>(ids.size() / 2);
    uint64_t cost_a = 0, cost_b = 0;
    std::vector<SiteGroup> groups = groupSites(points, sites, std::vector<size_t>(ids.begin(), middle), coarsest, passes, &cost_a);
    std::vector<SiteGroup> rest = groupSites(points, sites, std::vector<size_t>(middle, ids.end()), coarsest, passes, &cost_b);
    if (fits && *cost <= cost_a + cost_b) return {SiteGroup{box, std::move(ids)}};
    *cost = cost_a + cost_b;
    groups.insert(groups.end(), std::make_move_iterator(rest.begin()), std::make_move_iterator(rest.end()));
    return groups;
}

struct FinishedSite {
    float height = 0.0f;                        // bilinear at the site
    float rise_east = 0.0f, rise_south = 0.0f;  // plane fitted over the 7x7 pixels, metres per metre
    float wide_east = 0.0f, wide_south = 0.0f;  // and over the square of wideHalf
};

// Least-squares rise (metres per metre east and south) of the plane over +-half pixels around
// (cx, cy) of `h`.
std::pair<float, float> fittedRise(const Heightfield& h, int cx, int cy, int half) {
    double east = 0.0, south = 0.0;
    for (int dy = -half; dy <= half; ++dy)
        for (int dx = -half; dx <= half; ++dx) {
            east += dx * static_cast<double>(h.at(cx + dx, cy + dy));
            south += dy * static_cast<double>(h.at(cx + dx, cy + dy));
        }
    // The sum of dx^2 over the square: its side times sum_{-half..half} k^2.
    const double norm = (2.0 * half + 1.0) * half * (half + 1.0) * (2.0 * half + 1.0) / 3.0;
    return {static_cast<float>(east / (norm * h.meters_per_pixel_x)), static_cast<float>(south / (norm * h.meters_per_pixel_y))};
}

// The finished sites of `group` (level 0, one synthesis of its window: bit for bit what a window per
// site gives, windowed determinism): each site's height bilinear over the 2x2 pixels around it,
// whose centres are at whole coordinates, and the planes of `plane` fitted over their 7x7 pixels
// and over half their radius.
Status measureSites(Synthesizer& synthesizer, const SynthesisParams& params, const std::vector<PointConstraint>& points,
                    const std::vector<SitePlane>& plane, const SiteGroup& group, std::vector<FinishedSite>& sites) {
    auto out = synthesizer.synthesize(group.window, params, 0, false);
    if (!out) return out.status().withContext("point constraint " + std::to_string(group.points.front()));
    const Heightfield& h = out->heights;
    for (size_t i : group.points) {
        const PointConstraint& p = points[i];
        FinishedSite& site = sites[i];
        const double fx = std::floor(p.x), fy = std::floor(p.y);
        const int x = static_cast<int>(static_cast<int64_t>(fx) - group.window.x);
        const int y = static_cast<int>(static_cast<int64_t>(fy) - group.window.y);
        const float tx = static_cast<float>(p.x - fx), ty = static_cast<float>(p.y - fy);
        const float top = h.at(x, y) + (h.at(x + 1, y) - h.at(x, y)) * tx;
        const float bottom = h.at(x, y + 1) + (h.at(x + 1, y + 1) - h.at(x, y + 1)) * tx;
        site.height = top + (bottom - top) * ty;
        if (plane[i] == SitePlane::None) continue;
        const int cx = static_cast<int>(std::llround(p.x) - group.window.x), cy = static_cast<int>(std::llround(p.y) - group.window.y);
        std::tie(site.rise_east, site.rise_south) = fittedRise(h, cx, cy, 3);
        if (plane[i] == SitePlane::Wide) std::tie(site.wide_east, site.wide_south) = fittedRise(h, cx, cy, wideHalf(p));
    }
    return Status::ok();
}

// The rise the point asks for, metres per metre east and south.
std::pair<float, float> askedRise(const PointConstraint& p) {
    const double kDegree = 3.14159265358979323846 / 180.0;
    const double rise = std::tan(p.slope_angle_deg * kDegree), direction = p.slope_direction_deg * kDegree;
    return {static_cast<float>(rise * std::sin(direction)), static_cast<float>(-rise * std::cos(direction))};
}

struct PointSearch {
    synth::LiftSearch height, east, south, wide_east, wide_south;
    PointConstraint best;  // its lifts in the best round
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
    const double mpp = synthesizer.database().meters_per_pixel;
    std::vector<PointSearch> searches(points.size());
    std::vector<uint8_t> tilted(points.size(), 0), wide_held(points.size(), 1);
    std::vector<SitePlane> planes(points.size(), SitePlane::None);
    std::vector<PixelWindow> site_windows(points.size());
    for (size_t i : moving) {
        // Slopes are held over the site's own pixels only where the free levels hold the site.
        tilted[i] = params.hold_on_free_levels && points[i].slope_angle_deg >= kMinTiltedSlopeDeg;
        if (!tilted[i]) points[i].tilt_east = points[i].tilt_south = points[i].wide_tilt_east = points[i].wide_tilt_south = 0.0f;
        // The first round measures every tilted site's wide plane; later rounds only those that
        // miss or have a wide tilt (most hold untilted, and their window is the radius's size).
        planes[i] = tilted[i] ? SitePlane::Wide : SitePlane::None;
    }
    std::vector<SiteGroup> groups;
    auto regroup = [&] {
        for (size_t i : moving) site_windows[i] = siteWindow(points[i], planes[i]);
        uint64_t cost = 0;
        groups = groupSites(points, site_windows, moving, synth::coarsestLevel(synthesizer.database(), probe),
                            probe.correction_passes, &cost);
    };
    if (!moving.empty()) regroup();
    std::vector<FinishedSite> finished(points.size());
    float best_worst = std::numeric_limits<float>::infinity();
    for (int round = 0; round < options.max_rounds && !moving.empty(); ++round) {
        for (const SiteGroup& group : groups)
            if (Status s = measureSites(synthesizer, probe, points, planes, group, finished); !s) return s;
        // Worst miss in metres: the height at the site, or the plane's error at the 7x7's edge.
        float worst = 0.0f;
        bool held = true;
        for (size_t i : moving) {
            PointConstraint& p = points[i];
            const FinishedSite& site = finished[i];
            const float residual = site.height - p.height_m;
            searches[i].height.record(p.lift_m, residual, round);
            worst = std::max(worst, std::fabs(residual));
            held = held && std::fabs(residual) <= options.tolerance_m;
            if (!tilted[i]) continue;
            const auto [east, south] = askedRise(p);
            const float miss_east = site.rise_east - east, miss_south = site.rise_south - south;
            searches[i].east.record(p.tilt_east, miss_east, round);
            searches[i].south.record(p.tilt_south, miss_south, round);
            const float miss = std::hypot(miss_east, miss_south);
            worst = std::max(worst, static_cast<float>(miss * 3.0 * mpp));
            held = held && miss <= kTiltTolerance * std::hypot(east, south);
            if (planes[i] != SitePlane::Wide) continue;
            // The wide plane, with the same tolerance, and weighed like the 7x7 one (its error 3 px
            // out): its own edge would outweigh every height.
            const float wide_east = site.wide_east - east, wide_south = site.wide_south - south;
            searches[i].wide_east.record(p.wide_tilt_east, wide_east, round);
            searches[i].wide_south.record(p.wide_tilt_south, wide_south, round);
            const float wide = std::hypot(wide_east, wide_south);
            worst = std::max(worst, static_cast<float>(wide * 3.0 * mpp));
            wide_held[i] = wide <= kTiltTolerance * std::hypot(east, south);
            held = held && wide_held[i];
        }
        // The lifts of a whole round were synthesized together, so the best round is what is kept.
        if (worst < best_worst) {
            best_worst = worst;
            for (size_t i : moving) searches[i].best.takeLifts(points[i]);
        }
        if (held) break;
        for (size_t i : moving) {
            points[i].lift_m = searches[i].height.next();
            if (!tilted[i]) continue;
            points[i].tilt_east = searches[i].east.next(), points[i].tilt_south = searches[i].south.next();
            // Most wide planes hold untilted: they move only while they miss.
            if (!wide_held[i]) points[i].wide_tilt_east = searches[i].wide_east.next(), points[i].wide_tilt_south = searches[i].wide_south.next();
        }
        if (round > 0) continue;
        bool narrowed = false;
        for (size_t i : moving)
            if (planes[i] == SitePlane::Wide && wide_held[i] && points[i].wide_tilt_east == 0.0f && points[i].wide_tilt_south == 0.0f)
                planes[i] = SitePlane::Own, narrowed = true;
        if (narrowed) regroup();
    }
    for (size_t i : moving) points[i].takeLifts(searches[i].best);
    return std::shared_ptr<const SynthesisConstraints>(std::move(lifted));
}

}  // namespace terrasynth
