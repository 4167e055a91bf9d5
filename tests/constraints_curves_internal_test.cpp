// Curve constraints (Gain et al. 2015 s3, s5.1) rasterised into the correction kernel's blend sums.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "constraints/curve_envelope.h"
#include "constraints/curve_field.h"
#include "constraints/curve_geometry.h"
#include "constraints/curve_junctions.h"
#include "constraints/curve_profile.h"
#include "constraints/curve_raster.h"

namespace terrasynth::constraints {
namespace {

constexpr double kMpp = 10.0;  // metres per level-0 pixel
constexpr double kPi = 3.14159265358979323846;

CurveWidget widget(double t, float height, float left_gradient, float right_gradient, float left_reach, float right_reach) {
    CurveWidget w;
    w.t = t;
    w.height_m = height;
    w.left_gradient = left_gradient;
    w.right_gradient = right_gradient;
    w.left_reach_px = left_reach;
    w.right_reach_px = right_reach;
    return w;
}

CurveConstraint straight(double x0, double y0, double x1, double y1, std::vector<CurveWidget> widgets) {
    CurveConstraint c;
    c.course = {{x0, y0}, {x1, y1}};
    c.spline = false;
    c.widgets = std::move(widgets);
    return c;
}

double centre(int p, int level) { return (p + 0.5) * double(1 << level) - 0.5; }

struct Sums {
    core::LevelRegion region;
    std::vector<float> v;
    bool affected(int x, int y) const { return at(x, y)[0] > 0.0f; }
    double target(int x, int y) const { return at(x, y)[1] / at(x, y)[0]; }
    double distance(int x, int y) const { return at(x, y)[2] / at(x, y)[0]; }
    const float* at(int x, int y) const {
        return &v[3 * (static_cast<size_t>(y - region.y) * region.width + (x - region.x))];
    }
};

Sums run(const std::vector<CurveConstraint>& curves, int level, core::LevelRegion region) {
    Sums s{region, std::vector<float>(3 * region.pixels(), 0.0f)};
    accumulateCurves(curves, level, region, kMpp, s.v);
    return s;
}

// One curve without junction handling, with or without isocurve smoothing.
Sums runSingle(const CurveConstraint& curve, int level, core::LevelRegion region, bool smooth) {
    Sums s{region, std::vector<float>(3 * region.pixels(), 0.0f)};
    const CourseSamples course = sampleCourse(curve.course, curve.spline);
    accumulateCurve(course, CurveProfile(curve.widgets, course.length), level, region, kMpp, smooth, s.v);
    return s;
}

TEST(ConstraintCurves, StraightCourseUsesEachSidesGradientWithinItsReach) {
    // Course heading east along y = 200: left is north (smaller y).
    const CurveConstraint curve = straight(100, 200, 400, 200, {widget(0.5, 1000, 0.2f, -0.5f, 14, 9)});
    const int level = 2;  // localisation 16 px > both reaches
    const core::LevelRegion region{20, 30, 90, 40};
    const Sums s = run({curve}, level, region);
    int left = 0, right = 0;
    for (int y = region.y; y < region.y + region.height; ++y)
        for (int x = region.x; x < region.x + region.width; ++x) {
            const double cx = centre(x, level), cy = centre(y, level);
            if (cx < 110 || cx > 390) continue;  // the caps are tested separately
            const double d = std::abs(cy - 200);
            const bool is_left = cy < 200;
            const double reach = is_left ? 14 : 9, gradient = is_left ? 0.2 : -0.5;
            if (d > reach + 0.01) {
                EXPECT_FALSE(s.affected(x, y)) << "pixel " << x << "," << y << " at d " << d;
                continue;
            }
            if (d > reach - 0.01) continue;
            ASSERT_TRUE(s.affected(x, y)) << "pixel " << x << "," << y << " at d " << d;
            EXPECT_NEAR(s.distance(x, y), d, 1e-3);
            EXPECT_NEAR(s.target(x, y), 1000 + gradient * d * kMpp, 0.02);
            (is_left ? left : right)++;
        }
    EXPECT_GT(left, 100);
    EXPECT_GT(right, 100);
}

TEST(ConstraintCurves, SameDistanceOnBothSidesGivesEachSideItsGradient) {
    const CurveConstraint curve = straight(0, 201.5, 400, 201.5, {widget(0, 500, 0.3f, -0.1f, 12, 12)});
    const int level = 2;  // pixel rows at y = 4 p + 1.5: rows 48 and 52 are 8 px north and south
    const Sums s = run({curve}, level, {0, 40, 100, 20});
    for (int x = 10; x < 90; ++x) {
        ASSERT_TRUE(s.affected(x, 48) && s.affected(x, 52));
        EXPECT_NEAR(s.distance(x, 48), 8.0, 1e-3);
        EXPECT_NEAR(s.distance(x, 52), 8.0, 1e-3);
        EXPECT_NEAR(s.target(x, 48), 500 + 0.3 * 8 * kMpp, 0.02);
        EXPECT_NEAR(s.target(x, 52), 500 - 0.1 * 8 * kMpp, 0.02);
    }
}

TEST(ConstraintCurves, ReachIsLocalisedPerLevel) {
    const CurveConstraint curve = straight(-2000, 1000.5, 3000, 1000.5, {widget(0, 0, 0, 0, 200, 200)});
    for (int level = 2; level <= 5; ++level) {
        const double localised = std::min(200.0, 4.0 * (1 << level));
        const int cy = 1000 >> level;
        const core::LevelRegion region{0, cy - 10, 8, 21};
        const Sums s = run({curve}, level, region);
        double farthest = 0;
        for (int y = region.y; y < region.y + region.height; ++y) {
            const double d = std::abs(centre(y, level) - 1000.5);
            if (s.affected(3, y)) farthest = std::max(farthest, d);
            if (d < localised - 0.01) {
                EXPECT_TRUE(s.affected(3, y)) << "level " << level << " d " << d;
            }
            if (d > localised + 0.01) {
                EXPECT_FALSE(s.affected(3, y)) << "level " << level << " d " << d;
            }
        }
        EXPECT_GT(farthest, localised - (1 << level) - 0.01) << "level " << level;
    }
}

TEST(ConstraintCurves, HermiteInterpolationReproducesWidgetsAndIsSmooth) {
    const std::vector<CurveWidget> widgets = {widget(0.2, 100, 0.1f, 0, 8, 8), widget(0.5, 400, 0.5f, 0, 16, 4),
                                              widget(0.8, 250, -0.2f, 0, 4, 12)};
    const CurveProfile profile(widgets, 400.0);
    for (const CurveWidget& w : widgets) {
        const CurveProperties p = profile.widgetsAt(w.t);
        EXPECT_NEAR(p.height, w.height_m, 1e-9);
        EXPECT_NEAR(p.left_gradient, w.left_gradient, 1e-6);
        EXPECT_NEAR(p.left_reach, w.left_reach_px, 1e-6);
        EXPECT_NEAR(p.right_reach, w.right_reach_px, 1e-6);
    }
    // Constant beyond the first and last widget.
    EXPECT_NEAR(profile.widgetsAt(0.0).height, 100, 1e-9);
    EXPECT_NEAR(profile.widgetsAt(1.0).height, 250, 1e-9);
    // C1: first differences change by O(h^2) everywhere, including across widgets and the ends.
    const double h = 1e-3;
    double worst = 0;
    for (double t = 0.01; t < 0.99; t += 0.001) {
        const double second = profile.widgetsAt(t + h).height - 2 * profile.widgetsAt(t).height + profile.widgetsAt(t - h).height;
        worst = std::max(worst, std::abs(second));
    }
    EXPECT_LT(worst, 0.02);  // |h''| * h^2 with |h''| about 1e4 m per unit t^2
    // Smooth in between: no overshoot beyond the neighbouring widgets' range by more than 15%.
    for (double t = 0.2; t <= 0.5; t += 0.01) EXPECT_LE(profile.widgetsAt(t).height, 400 + 45);

    // Through the rasteriser: pixels on the course at the widgets' t get the widgets' heights.
    CurveConstraint curve = straight(1.5, 201.5, 401.5, 201.5, widgets);  // t = pixel x / 100 at level 2
    const Sums s = run({curve}, 2, {0, 45, 101, 10});
    EXPECT_NEAR(s.target(20, 50), 100, 0.02);
    EXPECT_NEAR(s.target(50, 50), 400, 0.02);
    EXPECT_NEAR(s.target(80, 50), 250, 0.02);
    // Between widgets the interpolated left reach decides the extent: at t = 0.5 it is 16.
    EXPECT_TRUE(s.affected(50, 47));  // 12 px north
    EXPECT_FALSE(s.affected(80, 47));  // reach 4 at t = 0.8
}

TEST(ConstraintCurves, EndCapsInterpolateLeftAndRightAroundTheEnd) {
    // Left (north) reach 6, right (south) reach 15; gradients 0.1 and 0.3.
    const std::vector<CurveWidget> widgets = {widget(0, 50, 0.1f, 0.3f, 6, 15)};
    int checked = 0, affected_ahead = 0;
    for (double shift : {0.0, 1.0, 2.0, 3.0}) {  // sub-pixel offsets sample more angles
        const double ex = 300 + shift, ey = 200 + 0.7 * shift;
        const CurveConstraint curve = straight(100 + shift, ey, ex, ey, widgets);
        const int level = 2;
        const core::LevelRegion region{70, 40, 15, 22};
        const Sums s = run({curve}, level, region);
        for (int y = region.y; y < region.y + region.height; ++y)
            for (int x = region.x; x < region.x + region.width; ++x) {
                const double vx = centre(x, level) - ex, vy = centre(y, level) - ey;
                if (vx <= 0) continue;  // only pixels beyond the end
                const double d = std::hypot(vx, vy);
                const double leftness = std::atan2(-vy, vx) / kPi + 0.5;
                const double w = leftness * leftness * (3 - 2 * leftness);
                const double reach = 15 + (6 - 15) * w, gradient = 0.3 + (0.1 - 0.3) * w;
                if (d > reach + 0.01) {
                    EXPECT_FALSE(s.affected(x, y));
                } else if (d < reach - 0.01) {
                    ASSERT_TRUE(s.affected(x, y)) << "cap pixel at angle " << leftness << " d " << d;
                    EXPECT_NEAR(s.target(x, y), 50 + gradient * d * kMpp, 0.02);
                    if (std::abs(vy) < 2) ++affected_ahead;
                    ++checked;
                }
            }
    }
    EXPECT_GT(checked, 40);
    EXPECT_GT(affected_ahead, 4);
    // The angular reach is smooth: it joins the sides with zero angular slope.
    const CurveProperties end{0, 0.1, 0.3, 6, 15};
    EXPECT_NEAR(capProperties(end, 0.0).left_reach, 15, 1e-9);
    EXPECT_NEAR(capProperties(end, 1.0).left_reach, 6, 1e-9);
    EXPECT_NEAR(capProperties(end, 0.5).left_reach, 10.5, 1e-9);
    EXPECT_NEAR(capProperties(end, 1e-4).left_reach, 15, 1e-5);
    EXPECT_NEAR(capProperties(end, 1 - 1e-4).left_reach, 6, 1e-5);
}

// Fraction of inside pixels within `radius` of the most enclosed boundary pixel of a window: 1/2 on
// a straight boundary, near 1 at the tip of a sharp notch in the envelope.
double sharpestNotch(const std::vector<uint8_t>& m, int width, int x0, int y0, int x1, int y1, int radius) {
    double worst = 0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            auto in = [&](int px, int py) { return m[static_cast<size_t>(py) * width + px] != 0; };
            if (!in(x, y) || (in(x - 1, y) && in(x + 1, y) && in(x, y - 1) && in(x, y + 1))) continue;
            int inside = 0, all = 0;
            for (int dy = -radius; dy <= radius; ++dy)
                for (int dx = -radius; dx <= radius; ++dx) {
                    if (dx * dx + dy * dy > radius * radius) continue;
                    ++all;
                    inside += in(x + dx, y + dy);
                }
            worst = std::max(worst, double(inside) / all);
        }
    return worst;
}

TEST(ConstraintCurves, IsocurveSmoothingRemovesTheStepAtTheMedialAxis) {
    // Figure 5: a course turning a right angle at (75, 75) with the reach jumping from 6 to 30 px
    // near the corner. On the concave side t jumps across the bisector, so the raw envelope has a
    // sharp notch there; the smoothed one must not.
    const int n = 100;
    EnvelopeGrid g;
    g.width = g.height = n;
    g.f.resize(n * n);
    g.s.resize(n * n);
    auto reach = [](double s) {
        const double u = std::clamp((s - 70) / 10, 0.0, 1.0);
        return 6 + 24 * u * u * (3 - 2 * u);
    };
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double ax = std::clamp(double(x), 0.0, 75.0), ay = std::clamp(double(y), 0.0, 75.0);
            const double d1 = std::hypot(x - ax, y - 75.0), d2 = std::hypot(x - 75.0, y - ay);
            const double s = d1 <= d2 ? ax : 150 - ay;
            g.f[y * n + x] = static_cast<float>(std::min(d1, d2) - reach(s));
            g.s[y * n + x] = s;
        }
    EnvelopeSmoothing raw;
    raw.enabled = false;
    EnvelopeSmoothing smooth;
    smooth.window = 60;  // twice the largest reach, as envelopeSmoothingForLevel chooses
    smooth.jump_arc_px = 3;
    const std::vector<uint8_t> before = envelopeMask(g, raw), after = envelopeMask(g, smooth);
    const double sharp_before = sharpestNotch(before, n, 8, 8, 74, 74, 6);
    const double sharp_after = sharpestNotch(after, n, 8, 8, 74, 74, 6);
    EXPECT_GT(sharp_before, 0.8);
    EXPECT_LT(sharp_after, 0.72);
    // Farther along the contour than the smoothing window from any jump (the horizontal arm's far
    // end) the envelope is exactly the raw one.
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < 8; ++x) EXPECT_EQ(before[y * n + x], after[y * n + x]) << x << "," << y;
}

TEST(ConstraintCurves, SmoothingChangesOnlyTheMedialAxisOfAnArcAndIsWindowIndependent) {
    // A 270-degree arc whose inner reach grows from 20 to 128 px: at level 4 (localisation 64) the
    // reach exceeds the 60 px radius, so t jumps on the concave side.
    CurveConstraint arc;
    for (int k = 0; k <= 12; ++k) {
        const double a = kPi * (0.25 + 1.5 * k / 12.0);
        arc.course.push_back({200 + 60 * std::cos(a), 200 + 60 * std::sin(a)});
    }
    arc.widgets = {widget(0, 0, 0, 0, 20, 20), widget(1, 0, 0, 0, 128, 128)};
    const int level = 4;
    const core::LevelRegion region{0, 0, 26, 26};
    const Sums raw = runSingle(arc, level, region, false), smoothed = runSingle(arc, level, region, true);
    int changed = 0;
    for (int y = 0; y < region.height; ++y)
        for (int x = 0; x < region.width; ++x) {
            if (raw.affected(x, y) == smoothed.affected(x, y)) continue;
            ++changed;
            // Changes stay near the medial axis: inside the arc's circle (its concave side) or in the
            // gap between its ends, where t jumps from one end to the other; never on the convex side.
            const double vx = centre(x, level) - 200, vy = centre(y, level) - 200;
            const bool in_gap = std::abs(std::atan2(vy, vx)) < kPi / 4;
            EXPECT_TRUE(std::hypot(vx, vy) < 60 || in_gap) << x << "," << y;
        }
    EXPECT_GT(changed, 0);
    // A sub-window gives bit-identical sums (synthesis windows must agree).
    const core::LevelRegion sub{9, 7, 9, 11};
    const Sums part = runSingle(arc, level, sub, true);
    for (int y = sub.y; y < sub.y + sub.height; ++y)
        for (int x = sub.x; x < sub.x + sub.width; ++x)
            for (int k = 0; k < 3; ++k) EXPECT_EQ(part.at(x, y)[k], smoothed.at(x, y)[k]);
}

TEST(ConstraintCurves, SumsAccumulateOverCurves) {
    const CurveConstraint a = straight(0, 100, 300, 120, {widget(0, 100, 0.1f, 0.2f, 12, 12)});
    const CurveConstraint b = straight(0, 130, 300, 110.5, {widget(0, 900, -0.1f, 0.0f, 16, 8)});  // crosses a
    const CurveConstraint c = straight(0, 200, 300, 200, {widget(0, 300, 0.0f, 0.0f, 16, 16)});
    const core::LevelRegion region{0, 15, 80, 45};
    const Sums sa = run({a}, 2, region), sc = run({c}, 2, region), sac = run({a, c}, 2, region);
    for (size_t i = 0; i < sa.v.size(); ++i) EXPECT_NEAR(sac.v[i], sa.v[i] + sc.v[i], 1e-4 * (1 + std::abs(sac.v[i])));
    // Existing sums are added to, not overwritten.
    Sums twice = sa;
    accumulateCurves({a}, 2, region, kMpp, twice.v);
    for (size_t i = 0; i < sa.v.size(); ++i) EXPECT_NEAR(twice.v[i], 2 * sa.v[i], 1e-4 * (1 + std::abs(sa.v[i])));
    // Crossing curves still add both contributions where both reach.
    const Sums sab = run({a, b}, 2, region);
    int both = 0;
    for (size_t i = 0; i < sab.v.size(); i += 3) both += sab.v[i] > 0;
    EXPECT_GT(both, 0);
}

TEST(ConstraintCurves, JunctionsAgreeOnHeight) {
    // Two straight courses crossing at (200, 200) with heights 100 and 300: both are pinned to 200.
    std::vector<CurveConstraint> curves = {straight(100, 200, 300, 200, {widget(0, 100, 0, 0, 12, 12)}),
                                           straight(200, 100, 200, 300, {widget(0, 300, 0, 0, 12, 12)})};
    std::vector<CourseSamples> courses;
    for (const CurveConstraint& c : curves) courses.push_back(sampleCourse(c.course, c.spline));
    const std::vector<CourseCrossing> crossings = findCrossings({&courses[0], &courses[1]}).crossings;
    ASSERT_EQ(crossings.size(), 1u);
    EXPECT_NEAR(crossings[0].x, 200, 1e-6);
    EXPECT_NEAR(crossings[0].y, 200, 1e-6);
    std::vector<CurveProfile> profiles = {CurveProfile(curves[0].widgets, courses[0].length),
                                          CurveProfile(curves[1].widgets, courses[1].length)};
    pinJunctions(crossings, profiles);
    EXPECT_NEAR(profiles[0].at(crossings[0].s_a).height, 200, 1e-9);
    EXPECT_NEAR(profiles[1].at(crossings[0].s_b).height, 200, 1e-9);
    EXPECT_NEAR(profiles[0].at(5).height, 100, 1e-9);  // beyond the blend (12 px) the widgets rule
    EXPECT_NEAR(profiles[1].at(195).height, 300, 1e-9);
    // Through the rasteriser: the pixel at the crossing sees 200 m from both curves.
    const Sums s = run(curves, 2, {40, 40,20, 20});
    const int p = 50;  // level-2 pixel whose centre (201.5, 201.5) is 1.5 px from each course
    ASSERT_TRUE(s.affected(p, p));
    EXPECT_NEAR(s.target(p, p), 200, 1.0);

    // A widget at the crossing specifies the junction height.
    curves[0].widgets.push_back(widget(0.5, 500, 0, 0, 12, 12));
    std::vector<CurveProfile> pinned = {CurveProfile(curves[0].widgets, courses[0].length),
                                        CurveProfile(curves[1].widgets, courses[1].length)};
    pinJunctions(crossings, pinned);
    EXPECT_NEAR(pinned[0].at(crossings[0].s_a).height, 500, 1e-9);
    EXPECT_NEAR(pinned[1].at(crossings[0].s_b).height, 500, 1e-9);
}

TEST(ConstraintCurves, SelfIntersectionIsAJunction) {
    // A loop: east, then north, then west, then south across the first leg.
    CurveConstraint loop;
    loop.spline = false;
    loop.course = {{0, 100}, {200, 100}, {200, 0}, {100, 0}, {100, 200}};
    loop.widgets = {widget(0, 0, 0, 0, 10, 10), widget(1, 800, 0, 0, 10, 10)};
    const CourseSamples course = sampleCourse(loop.course, loop.spline);
    const std::vector<CourseCrossing> crossings = findCrossings({&course}).crossings;
    ASSERT_EQ(crossings.size(), 1u);
    EXPECT_EQ(crossings[0].a, 0u);
    EXPECT_EQ(crossings[0].b, 0u);
    EXPECT_NEAR(crossings[0].x, 100, 1e-6);
    EXPECT_NEAR(crossings[0].y, 100, 1e-6);
    std::vector<CurveProfile> profiles = {CurveProfile(loop.widgets, course.length)};
    const double expected = 0.5 * (profiles[0].heightAt(crossings[0].s_a) + profiles[0].heightAt(crossings[0].s_b));
    pinJunctions(crossings, profiles);
    EXPECT_NEAR(profiles[0].at(crossings[0].s_a).height, expected, 1e-6);
    EXPECT_NEAR(profiles[0].at(crossings[0].s_b).height, expected, 1e-6);
}

TEST(ConstraintCurves, SplineCourseInterpolatesItsPointsSmoothly) {
    const std::vector<std::pair<double, double>> points = {{0, 0}, {100, 40}, {180, -20}, {260, 60}};
    const CourseSamples c = sampleCourse(points, true);
    ASSERT_GT(c.segments(), 200u);
    for (const auto& [px, py] : points) {
        double best = 1e9;
        for (size_t i = 0; i < c.x.size(); ++i) best = std::min(best, std::hypot(c.x[i] - px, c.y[i] - py));
        EXPECT_LT(best, 1e-9);
    }
    double worst_turn = 0, longest = 0;
    for (size_t i = 1; i + 1 < c.x.size(); ++i) {
        const double a = std::atan2(c.y[i] - c.y[i - 1], c.x[i] - c.x[i - 1]);
        const double b = std::atan2(c.y[i + 1] - c.y[i], c.x[i + 1] - c.x[i]);
        worst_turn = std::max(worst_turn, std::abs(std::remainder(b - a, 2 * kPi)));
        longest = std::max(longest, c.s[i + 1] - c.s[i]);
    }
    EXPECT_LT(worst_turn, 0.05);  // radians between consecutive ~1 px segments: no kinks
    EXPECT_LE(longest, kMaxSegmentPx + 1e-9);
    EXPECT_NEAR(c.length, c.s.back(), 1e-12);
    // The cached sampling is shared for an unchanged course.
    CurveConstraint curve;
    curve.course = points;
    EXPECT_EQ(cachedCourse(curve).get(), cachedCourse(curve).get());
}

}  // namespace
}  // namespace terrasynth::constraints
