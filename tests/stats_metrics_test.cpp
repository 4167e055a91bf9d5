// Slope, curvature, local relief and landform classes on analytic surfaces (where the answer is known
// exactly) and on real exemplars; bad input gives errors, not crashes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "terrasynth/terrain_stats.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

constexpr double kPi = 3.14159265358979323846;

// z = f(x_m, y_m) sampled at the given spacing; x east, y south, in metres.
template <class F>
Heightfield analytic(int w, int h, double mx, double my, F f) {
    Heightfield field(w, h, mx);
    field.meters_per_pixel_y = my;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) field.at(x, y) = static_cast<float>(f(x * mx, y * my));
    return field;
}

Heightfield transposed(const Heightfield& f) {
    Heightfield t(f.height, f.width, f.meters_per_pixel_y);
    t.meters_per_pixel_y = f.meters_per_pixel_x;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) t.at(y, x) = f.at(x, y);
    return t;
}

}  // namespace

TEST(StatsSlope, InclinedPlaneIsExactWithAnisotropicSpacing) {
    // Rises 0.3 m per metre east and falls 0.2 m per metre south, on 20 m x 35 m cells.
    const Heightfield plane = analytic(64, 48, 20.0, 35.0, [](double x, double y) { return 100.0 + 0.3 * x - 0.2 * y; });
    const double expected = std::atan(std::hypot(0.3, 0.2)) * 180.0 / kPi;
    const std::vector<float> slope = slopeDegrees(plane);
    for (int y = 1; y < plane.height - 1; ++y)
        for (int x = 1; x < plane.width - 1; ++x) ASSERT_NEAR(slope[y * plane.width + x], expected, 1e-3);

    auto stats = computeTerrainStats(plane);
    ASSERT_TRUE(stats) << stats.message();
    EXPECT_NEAR(stats->slope_deg.mean, expected, 1e-3);
    EXPECT_NEAR(stats->slope_deg.p10, expected, 1e-3);
    EXPECT_NEAR(stats->slope_deg.p90, expected, 1e-3);
    EXPECT_LT(stats->slope_deg.stddev, 1e-3);
    // A plane has no curvature and every sloping pixel is a planar backslope.
    EXPECT_LT(std::fabs(stats->profile_curvature.p99), 1e-6);
    EXPECT_LT(std::fabs(stats->plan_curvature.p99), 1e-6);
    EXPECT_NEAR(stats->landform_share[static_cast<int>(Landform::Backslope)], 1.0, 1e-12);
    EXPECT_EQ(stats->pit_share, 0.0);
    EXPECT_EQ(stats->depression_share, 0.0);
}

TEST(StatsCurvature, DomeAndBowlHaveTheirCurvatureWithConvexPositive) {
    // z = -c r^2 / 2 has second derivative -c in every direction: profile = plan = +c (convex).
    const double c = 2e-4;  // 1/m
    const Heightfield dome = analytic(65, 65, 10.0, 10.0, [&](double x, double y) {
        return 1000.0 - 0.5 * c * ((x - 320.0) * (x - 320.0) + (y - 320.0) * (y - 320.0));
    });
    const CurvatureMaps k = curvatures(dome);
    int checked = 0;
    for (int y = 2; y < 63; ++y)
        for (int x = 2; x < 63; ++x) {
            const size_t i = y * 65 + x;
            if (std::isnan(k.profile[i])) {
                EXPECT_TRUE(x == 32 && y == 32) << "only the summit lacks a gradient direction";
                continue;
            }
            ASSERT_NEAR(k.profile[i], c, 0.02 * c) << x << "," << y;
            ASSERT_NEAR(k.plan[i], c, 0.02 * c) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 3000);

    Heightfield bowl = dome;
    for (float& z : bowl.heights) z = 2000.0f - z;
    const CurvatureMaps kb = curvatures(bowl);
    EXPECT_NEAR(kb.profile[10 * 65 + 20], -c, 0.02 * c);
    EXPECT_NEAR(kb.plan[10 * 65 + 20], -c, 0.02 * c);
}

TEST(StatsLandforms, SlopingRidgeCrestAndValleyFloorAreClassified) {
    // A ridge along y that also falls southward at 10%: its crest has convex contours (plan > 0) and a
    // straight profile. The same shape upside down is a valley. c*spacing = 0.5 > the 0.05 threshold.
    const double c = 0.05;
    const Heightfield ridge = analytic(65, 65, 10.0, 10.0,
                                       [&](double x, double y) { return 1000.0 - 0.5 * c * (x - 320) * (x - 320) - 0.1 * y; });
    Heightfield valley = ridge;
    for (int y = 0; y < 65; ++y)
        for (int x = 0; x < 65; ++x) valley.at(x, y) = static_cast<float>(0.5 * c * (x * 10.0 - 320) * (x * 10.0 - 320) - y);
    const std::vector<uint8_t> rc = classifyLandforms(ridge), vc = classifyLandforms(valley);
    for (int y = 1; y < 64; ++y) {
        EXPECT_EQ(rc[y * 65 + 32], static_cast<uint8_t>(Landform::PeakRidge)) << "row " << y;
        EXPECT_EQ(vc[y * 65 + 32], static_cast<uint8_t>(Landform::ValleyChannel)) << "row " << y;
    }
    // Away from the crest the parabolic flanks steepen downhill: convex profile, a shoulder.
    EXPECT_EQ(rc[30 * 65 + 10], static_cast<uint8_t>(Landform::Shoulder));
    EXPECT_EQ(vc[30 * 65 + 10], static_cast<uint8_t>(Landform::Footslope));
    // A level field is flat.
    const Heightfield level(40, 40, 30.0, 500.0f);
    for (uint8_t v : classifyLandforms(level)) ASSERT_EQ(v, static_cast<uint8_t>(Landform::Flat));
}

TEST(StatsRelief, PlaneReliefIsWindowExtentTimesGradient) {
    const Heightfield plane = analytic(50, 40, 12.0, 12.0, [](double x, double y) { return 0.25 * x + 0.1 * y; });
    const std::vector<float> relief = localRelief(plane, 9);
    for (int y = 4; y < 36; ++y)
        for (int x = 4; x < 46; ++x) ASSERT_NEAR(relief[y * 50 + x], 8 * 12.0 * (0.25 + 0.1), 1e-3);
    // At a corner the window is clipped to 5x5.
    EXPECT_NEAR(relief[0], 4 * 12.0 * (0.25 + 0.1), 1e-3);
    auto stats = computeTerrainStats(plane);
    ASSERT_TRUE(stats) << stats.message();
    EXPECT_NEAR(stats->local_relief_m.median, 8 * 12.0 * 0.35, 1e-3);
}

TEST(StatsRealData, TransposingAnExemplarKeepsItsDistributions) {
    // The metrics must not prefer an axis: swapping x and y (and their spacings) of a real DEM leaves
    // slope, curvature, relief, pits and landforms unchanged.
    const Heightfield alaska = test::loadExemplarField("orom_alaska");
    auto a = computeTerrainStats(alaska);
    auto t = computeTerrainStats(transposed(alaska));
    ASSERT_TRUE(a && t);
    EXPECT_NEAR(a->slope_deg.mean, t->slope_deg.mean, 1e-9);
    EXPECT_NEAR(a->slope_deg.p90, t->slope_deg.p90, 1e-6);
    EXPECT_NEAR(a->profile_curvature.stddev, t->profile_curvature.stddev, 1e-9);
    EXPECT_NEAR(a->plan_curvature.median, t->plan_curvature.median, 1e-9);
    EXPECT_NEAR(a->local_relief_m.mean, t->local_relief_m.mean, 1e-6);
    EXPECT_EQ(a->pit_share, t->pit_share);
    EXPECT_EQ(a->depression_share, t->depression_share);
    for (int c = 0; c < kLandformCount; ++c) EXPECT_NEAR(a->landform_share[c], t->landform_share[c], 1e-5);
    EXPECT_NEAR(a->spectrum.slope_2d, t->spectrum.slope_2d, 1e-6);
    const StatsDistance d = compareStats(*a, *t);
    EXPECT_LT(d[Metric::Slope].value, 1e-9);
    EXPECT_LT(d[Metric::DrainageArea].value, 0.05) << "D8 ties may break differently, but only slightly";
}

TEST(StatsRealData, PlainHasMoreFlatGroundAndEverestSteeperSlopes) {
    auto butte = computeTerrainStats(test::loadExemplarField("wn_big_butte"));
    auto everest = computeTerrainStats(test::loadExemplarField("orom_himalaya-everest"));
    ASSERT_TRUE(butte && everest);
    const int flat = static_cast<int>(Landform::Flat);
    EXPECT_GT(butte->landform_share[flat], 0.5);
    EXPECT_LT(everest->landform_share[flat], 0.05);
    EXPECT_GT(everest->slope_deg.median, 3 * butte->slope_deg.median);
    double sum = 0.0;
    for (double s : everest->landform_share) sum += s;
    EXPECT_NEAR(sum, 1.0, 1e-9);
    // Mountains: ridges and valleys together outweigh planar slopes.
    EXPECT_GT(everest->landform_share[static_cast<int>(Landform::PeakRidge)] +
                  everest->landform_share[static_cast<int>(Landform::ValleyChannel)],
              everest->landform_share[static_cast<int>(Landform::Backslope)]);
}

TEST(StatsErrors, EmptyNanTinyAndBadSpacingAreErrorsNotCrashes) {
    auto empty = computeTerrainStats(Heightfield());
    ASSERT_FALSE(empty);
    EXPECT_NE(empty.message().find("empty"), std::string::npos) << empty.message();

    Heightfield nan_field(64, 64, 30.0, 10.0f);
    nan_field.at(5, 7) = std::numeric_limits<float>::quiet_NaN();
    auto nan = computeTerrainStats(nan_field);
    ASSERT_FALSE(nan);
    EXPECT_NE(nan.message().find("non-finite"), std::string::npos) << nan.message();
    EXPECT_NE(nan.message().find("x=5 y=7"), std::string::npos) << nan.message();

    Heightfield inf_spacing(64, 64, 30.0);
    inf_spacing.meters_per_pixel_y = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(computeTerrainStats(inf_spacing));

    Heightfield mismatched(64, 64, 30.0);
    mismatched.heights.resize(100);
    EXPECT_FALSE(computeTerrainStats(mismatched));

    auto tiny = computeTerrainStats(Heightfield(20, 64, 30.0));
    ASSERT_FALSE(tiny);
    EXPECT_NE(tiny.message().find("32x32"), std::string::npos) << tiny.message();
    EXPECT_FALSE(powerSpectrum(Heightfield(16, 16, 30.0)));

    EXPECT_FALSE(referenceSpread({}, 128));
    EXPECT_FALSE(referenceSpread({Heightfield(100, 100, 30.0)}, 16));
    auto one_piece = referenceSpread({Heightfield(100, 100, 30.0)}, 64);
    ASSERT_FALSE(one_piece);
    EXPECT_NE(one_piece.message().find("need at least 2"), std::string::npos) << one_piece.message();
    EXPECT_FALSE(referenceSpread({nan_field, nan_field}, 32));

    // A level field is legal: no slope, no curvature samples, an undefined spectral slope.
    auto level = computeTerrainStats(Heightfield(64, 64, 30.0, 250.0f));
    ASSERT_TRUE(level) << level.message();
    EXPECT_EQ(level->slope_deg.max, 0.0);
    EXPECT_EQ(level->profile_curvature.samples, 0u);
    EXPECT_TRUE(std::isnan(level->spectrum.slope_1d));
}
