// Cost limits that must not change results: the indexed junction pins, the binary-search
// widget snap, the linear crossing de-duplication and the clipped stroke painter each give exactly
// what the straightforward (quadratic or unclipped) version gave, written out here as the oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "constraints/curve_geometry.h"
#include "constraints/curve_junctions.h"
#include "constraints/curve_profile.h"
#include "terrasynth/constraints.h"

namespace terrasynth::constraints {
namespace {

// ---- Oracles: the code before the indexes, verbatim in behaviour ----

double pinnedHeightByScan(const CurveProfile& profile, double s) {
    double height = profile.widgetsAt(profile.t(s)).height;
    for (const JunctionPin& pin : profile.pins()) {
        const double w = junctionFalloff(std::abs(s - pin.s) / pin.blend_px);
        if (w > 0.0) height += w * (pin.height - profile.heightAt(pin.s));
    }
    return height;
}

bool widgetNearByScan(const std::vector<CurveWidget>& widgets, double length, double s, double snap, double* height) {
    std::vector<CurveWidget> sorted = widgets;
    std::stable_sort(sorted.begin(), sorted.end(), [](const CurveWidget& a, const CurveWidget& b) { return a.t < b.t; });
    for (const CurveWidget& w : sorted)
        if (std::abs(w.t * length - s) <= snap) {
            *height = w.height_m;
            return true;
        }
    return false;
}

// The brush of paintStroke stamped at every step of every segment, clipped per dab only.
void paintByEveryDab(TypePaint& paint, const std::vector<std::pair<double, double>>& line, double r, uint8_t value) {
    auto dab = [&](double gx, double gy) {
        const double cx = gx - static_cast<double>(paint.x), cy = gy - static_cast<double>(paint.y);
        const int y0 = static_cast<int>(std::max(0.0, std::floor(cy - r)));
        const int y1 = static_cast<int>(std::min(paint.height - 1.0, std::ceil(cy + r)));
        const int x0 = static_cast<int>(std::max(0.0, std::floor(cx - r)));
        const int x1 = static_cast<int>(std::min(paint.width - 1.0, std::ceil(cx + r)));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) paint.types[static_cast<size_t>(y) * paint.width + x] = value;
    };
    for (size_t i = 0; i < line.size(); ++i) {
        if (i == 0) {
            dab(line[0].first, line[0].second);
            continue;
        }
        const double dx = line[i].first - line[i - 1].first, dy = line[i].second - line[i - 1].second;
        const int steps = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / std::max(0.5, r * 0.5))));
        for (int s = 1; s <= steps; ++s) dab(line[i - 1].first + dx * s / steps, line[i - 1].second + dy * s / steps);
    }
}

// Every pair of segments tested (no grid), then the quadratic de-duplication findCrossings had.
std::vector<CourseCrossing> crossingsByEveryPair(const std::vector<const CourseSamples*>& courses) {
    std::vector<CourseCrossing> found;
    for (size_t ka = 0; ka < courses.size(); ++ka)
        for (size_t kb = ka; kb < courses.size(); ++kb) {
            const CourseSamples &a = *courses[ka], &b = *courses[kb];
            for (size_t i = 0; i < a.segments(); ++i)
                for (size_t j = ka == kb ? i + 1 : 0; j < b.segments(); ++j) {
                    if (ka == kb && (j - i <= 1 || (a.closed && i == 0 && j + 1 == a.segments()))) continue;
                    const double rx = a.x[i + 1] - a.x[i], ry = a.y[i + 1] - a.y[i];
                    const double sx = b.x[j + 1] - b.x[j], sy = b.y[j + 1] - b.y[j];
                    const double denom = rx * sy - ry * sx;
                    if (std::abs(denom) < 1e-12) continue;
                    const double qpx = b.x[j] - a.x[i], qpy = b.y[j] - a.y[i];
                    const double u = (qpx * sy - qpy * sx) / denom, v = (qpx * ry - qpy * rx) / denom;
                    if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0)) continue;
                    CourseCrossing x;
                    x.a = ka, x.b = kb;
                    x.s_a = a.s[i] + u * (a.s[i + 1] - a.s[i]);
                    x.s_b = b.s[j] + v * (b.s[j + 1] - b.s[j]);
                    x.x = a.x[i] + u * rx, x.y = a.y[i] + u * ry;
                    found.push_back(x);
                }
        }
    std::sort(found.begin(), found.end(), [](const CourseCrossing& l, const CourseCrossing& r) {
        return std::tie(l.a, l.b, l.s_a, l.s_b) < std::tie(r.a, r.b, r.s_a, r.s_b);
    });
    std::vector<CourseCrossing> unique;
    for (const CourseCrossing& x : found) {
        const bool repeat = std::any_of(unique.begin(), unique.end(), [&](const CourseCrossing& u) {
            return u.a == x.a && u.b == x.b && std::abs(u.s_a - x.s_a) < 1.0 && std::abs(u.s_b - x.s_b) < 1.0;
        });
        if (!repeat) unique.push_back(x);
    }
    return unique;
}

std::vector<std::pair<double, double>> randomCourse(std::mt19937& rng, int n, double lo, double hi) {
    std::uniform_real_distribution<double> u(lo, hi);
    std::vector<std::pair<double, double>> c;
    for (int i = 0; i < n; ++i) c.emplace_back(u(rng), u(rng));
    return c;
}

// ---- The indexed versions agree with the oracles, bit for bit ----

TEST(ConstraintHardening, IndexedJunctionPinsSumLikeEveryPin) {
    std::mt19937 rng(20);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<CurveWidget> widgets;
    for (int k = 0; k < 7; ++k) widgets.push_back({k / 6.0, float(1000 + 300 * u(rng)), 0.1f, -0.2f, 20.0f, 30.0f});
    CurveProfile profile(widgets, 800.0);
    std::vector<JunctionPin> pins;
    for (int k = 0; k < 300; ++k) pins.push_back({800.0 * u(rng), 900.0 + 500.0 * u(rng), 4.0 + 60.0 * u(rng)});
    profile.setPins(pins);
    for (int k = 0; k <= 4000; ++k) {
        const double s = -20.0 + 840.0 * k / 4000.0;
        ASSERT_EQ(profile.at(s).height, pinnedHeightByScan(profile, s)) << "at s = " << s;
    }
}

TEST(ConstraintHardening, WidgetSnapBySearchFindsWhatTheScanFinds) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<CurveWidget> widgets;
    for (int k = 0; k < 40; ++k) widgets.push_back({u(rng), float(k), 0, 0, 1, 1});
    widgets.push_back(widgets[5]);  // equal t: the first in stable order wins
    widgets.back().height_m = 99.0f;
    std::stable_sort(widgets.begin(), widgets.end(), [](const CurveWidget& a, const CurveWidget& b) { return a.t < b.t; });
    const CurveProfile profile(widgets, 500.0);
    for (int k = 0; k <= 5000; ++k) {
        const double s = -5.0 + 510.0 * k / 5000.0;
        double a = -1, b = -1;
        const bool found = profile.widgetNear(s, kJunctionWidgetSnapPx, &a);
        ASSERT_EQ(found, widgetNearByScan(widgets, 500.0, s, kJunctionWidgetSnapPx, &b)) << "s = " << s;
        if (found) {
            ASSERT_EQ(a, b) << "s = " << s;
        }
    }
}

TEST(ConstraintHardening, CrossingsDeduplicateLikeTheQuadraticScan) {
    std::mt19937 rng(11);
    std::vector<CourseSamples> courses;
    for (int k = 0; k < 3; ++k) courses.push_back(sampleCourse(randomCourse(rng, 25, 0.0, 120.0), k != 1));
    const std::vector<const CourseSamples*> raw = {&courses[0], &courses[1], &courses[2]};
    const CrossingSearch search = findCrossings(raw);
    ASSERT_TRUE(search.complete);
    const std::vector<CourseCrossing> oracle = crossingsByEveryPair(raw);
    ASSERT_GT(oracle.size(), 50u);
    ASSERT_EQ(search.crossings.size(), oracle.size());
    for (size_t i = 0; i < oracle.size(); ++i) {
        EXPECT_EQ(search.crossings[i].a, oracle[i].a);
        EXPECT_EQ(search.crossings[i].b, oracle[i].b);
        EXPECT_EQ(search.crossings[i].s_a, oracle[i].s_a);
        EXPECT_EQ(search.crossings[i].s_b, oracle[i].s_b);
    }
}

TEST(ConstraintHardening, AScribbleStopsTheCrossingSearch) {
    // 4000 points thrown into a 60-pixel square: thousands of segments per grid cell.
    std::mt19937 rng(5);
    const CourseSamples scribble = sampleCourse(randomCourse(rng, 4000, 0.0, 60.0), false);
    const CrossingSearch search = findCrossings({&scribble});
    EXPECT_FALSE(search.complete);
}

TEST(ConstraintHardening, ClippedStrokePaintsWhatEveryDabPaints) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 60; ++trial) {
        TypePaint a;
        a.x = -30 + static_cast<int64_t>(60 * u(rng)), a.y = -20 + static_cast<int64_t>(40 * u(rng));
        a.width = 20 + static_cast<int>(90 * u(rng)), a.height = 15 + static_cast<int>(70 * u(rng));
        a.types.assign(static_cast<size_t>(a.width) * a.height, TypePaint::kUnpainted);
        TypePaint b = a;
        const double r = trial % 3 == 0 ? 0.5 + 2 * u(rng) : 0.5 + 40 * u(rng);
        const auto line = randomCourse(rng, 1 + trial % 6, -150.0, 200.0);
        paintStroke(a, line, r, static_cast<uint8_t>(trial % 4));
        paintByEveryDab(b, line, r, static_cast<uint8_t>(trial % 4));
        ASSERT_EQ(a.types, b.types) << "trial " << trial << " radius " << r;
    }
}

TEST(ConstraintHardening, StrokesFromFarAwayCostWhatTheirPartOverThePaintCosts) {
    TypePaint paint;
    paint.width = paint.height = 128;
    paint.types.assign(128 * 128, TypePaint::kUnpainted);
    // Crossing the paint from 1e8 pixels away with a 1-pixel brush: ~2e8 dabs unclipped.
    const std::vector<std::pair<double, double>> line = {{-1e8, 64.0}, {1e8, 64.0}};
    EXPECT_LT(strokePaintCost(paint, line, 1.0), 2000000u);
    paintStroke(paint, line, 1.0, 3);
    EXPECT_EQ(paint.types[64 * 128 + 5], 3);
    EXPECT_EQ(paint.types[60 * 128 + 5], TypePaint::kUnpainted);
    // A huge brush covers everything in a handful of dabs.
    EXPECT_LT(strokePaintCost(paint, {{-1e9, -1e9}, {1e9, 1e9}}, 1e5), 100u * 128 * 128);
    paintStroke(paint, {{-1e9, -1e9}, {1e9, 1e9}}, 1e5, 9);
    EXPECT_TRUE(std::all_of(paint.types.begin(), paint.types.end(), [](uint8_t v) { return v == 9; }));
}

}  // namespace
}  // namespace terrasynth::constraints
