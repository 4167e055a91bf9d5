// Depression filling, D8 drainage area and pit shares: analytic surfaces with known flow, and real DEMs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "terrasynth/terrain_stats.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

template <class F>
Heightfield analytic(int n, double spacing, F f) {
    Heightfield field(n, n, spacing);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) field.at(x, y) = static_cast<float>(f(x, y));
    return field;
}

bool onBorder(const Heightfield& f, int x, int y) { return x == 0 || y == 0 || x == f.width - 1 || y == f.height - 1; }

// Border cells pass nothing on: their areas together are everything that leaves the field.
double areaLeavingTheField(const Heightfield& f, const std::vector<double>& area) {
    double out = 0.0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
            if (onBorder(f, x, y)) out += area[y * f.width + x];
    return out;
}

Heightfield whiteNoise(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 100.0f);
    Heightfield f(n, n, 30.0);
    for (float& z : f.heights) z = u(rng);
    return f;
}

}  // namespace

TEST(StatsDrainage, PlaneFallingSouthDrainsStraightDownItsColumns) {
    // Steepest descent on z = -0.1 * y_m is due south; each cell collects its column above it, except
    // that the northern border row drains off the field and passes nothing on.
    const double spacing = 25.0;
    const Heightfield plane = analytic(40, spacing, [&](int, int y) { return 500.0 - 0.1 * y * spacing; });
    const std::vector<double> area = drainageArea(plane);
    for (int y = 0; y < 40; ++y)
        for (int x = 1; x < 39; ++x) ASSERT_DOUBLE_EQ(area[y * 40 + x], std::max(1, y) * spacing * spacing) << x << "," << y;
}

TEST(StatsDrainage, ConeDivergesWhileFunnelConverges) {
    const int n = 129;
    const double spacing = 10.0, cell = spacing * spacing;
    auto r = [](int x, int y) { return std::hypot(x - 64.0, y - 64.0); };
    const Heightfield cone = analytic(n, spacing, [&](int x, int y) { return 800.0 - 5.0 * r(x, y); });
    const Heightfield funnel = analytic(n, spacing, [&](int x, int y) { return 100.0 + 5.0 * r(x, y); });
    const std::vector<double> cone_area = drainageArea(cone), funnel_area = drainageArea(funnel);
    const double total = n * n * cell;

    // Water is conserved: everything leaves through the border, nothing is lost or counted twice.
    EXPECT_NEAR(areaLeavingTheField(cone, cone_area), total, 1e-6 * total);
    EXPECT_NEAR(areaLeavingTheField(funnel, funnel_area), total, 1e-6 * total);

    // On the cone flow spreads outward along straight lines: the summit receives nothing, and no cell
    // collects more than a few rays' worth of cells.
    EXPECT_DOUBLE_EQ(cone_area[64 * n + 64], cell);
    const double cone_max = *std::max_element(cone_area.begin(), cone_area.end());
    EXPECT_LT(cone_max, 4.0 * n * cell);
    // The funnel is a depression: filling makes its inscribed disc a lake that spills at the four
    // edge midpoints, so a few outlets carry the whole disc.
    const double funnel_max = *std::max_element(funnel_area.begin(), funnel_area.end());
    EXPECT_GT(funnel_max, 0.15 * total);
    EXPECT_GT(funnel_max, 20.0 * cone_max);
}

TEST(StatsFill, RealDemHasNoInteriorPitAfterFillingAndRefillingChangesNothing) {
    for (const char* stem : {"orom_alaska", "orom_sahara"}) {
        SCOPED_TRACE(stem);
        const Heightfield dem = test::loadExemplarField(stem);
        const Heightfield plain = fillDepressions(dem, false);
        const Heightfield eps = fillDepressions(dem, true);
        size_t raised = 0;
        for (size_t i = 0; i < dem.size(); ++i) {
            ASSERT_GE(plain.heights[i], dem.heights[i]);
            ASSERT_GE(eps.heights[i], plain.heights[i]);
            raised += plain.heights[i] > dem.heights[i];
        }
        EXPECT_GT(raised, 0u) << "real SRTM data has closed depressions to fill";
        for (uint8_t p : pitMask(plain)) ASSERT_EQ(p, 0);
        // With epsilon every interior cell has a strictly lower neighbour, so D8 flow is defined.
        for (int y = 1; y < dem.height - 1; ++y)
            for (int x = 1; x < dem.width - 1; ++x) {
                float lowest = eps.at(x, y);
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) lowest = std::min(lowest, eps.at(x + dx, y + dy));
                ASSERT_LT(lowest, eps.at(x, y)) << x << "," << y;
            }
        EXPECT_EQ(fillDepressions(plain, false).heights, plain.heights);
        EXPECT_EQ(fillDepressions(eps, true).heights, eps.heights);
    }
}

TEST(StatsFill, CarvedHoleFillsToItsLowestNeighbour) {
    Heightfield dem = test::loadExemplarField("orom_rockies");
    dem.at(300, 200) -= 800.0f;
    const Heightfield after = fillDepressions(dem, false);
    float rim = std::numeric_limits<float>::infinity();
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            if (dx || dy) rim = std::min(rim, after.at(300 + dx, 200 + dy));
    EXPECT_EQ(after.at(300, 200), rim);
    EXPECT_GT(after.at(300, 200), dem.at(300, 200));
    EXPECT_EQ(pitMask(dem)[200 * dem.width + 300], 1);
}

TEST(StatsPits, WhiteNoiseIsFullOfPitsWhileRealDemsHaveFew) {
    // Of nine independent heights each is the lowest with probability 1/9.
    auto noise = computeTerrainStats(whiteNoise(256, 7));
    ASSERT_TRUE(noise) << noise.message();
    EXPECT_NEAR(noise->pit_share, 1.0 / 9.0, 0.01);
    EXPECT_GT(noise->depression_share, 0.3);
    for (const char* stem : {"orom_alaska", "orom_appalachians", "orom_himalaya-everest", "orom_rockies"}) {
        auto real = computeTerrainStats(test::loadExemplarField(stem));
        ASSERT_TRUE(real) << real.message();
        EXPECT_LT(real->pit_share, 0.01) << stem;
        EXPECT_LT(real->pit_share, noise->pit_share / 10) << stem;
        EXPECT_LT(real->depression_share, 0.05) << stem;
    }
}

TEST(StatsDrainage, RealMountainNetworksFollowTheirPowerLaw) {
    // P(A >= a) ~ a^-tau with tau near 0.43-0.5 for river networks (Rodriguez-Iturbe & Rinaldo 1997).
    for (const char* stem : {"orom_alaska", "orom_himalaya-everest", "orom_rockies"}) {
        auto real = computeTerrainStats(test::loadExemplarField(stem));
        ASSERT_TRUE(real) << real.message();
        EXPECT_GT(real->drainage_exceedance_exponent, 0.35) << stem;
        EXPECT_LT(real->drainage_exceedance_exponent, 0.65) << stem;
    }
}
