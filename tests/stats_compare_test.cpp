// Distances between terrains: the histogram distances themselves, real quadrants against contrasting
// landscapes, and the reference spread used to judge synthesized terrain.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "terrasynth/terrain_stats.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

TerrainStats statsOf(const Heightfield& f) {
    auto s = computeTerrainStats(f);
    EXPECT_TRUE(s) << s.message();
    return s ? std::move(s.value()) : TerrainStats();
}

Heightfield quadrant(const Heightfield& f, int q) {
    const int w = f.width / 2, h = f.height / 2;
    return test::crop(f, (q % 2) * w, (q / 2) * h, w, h);
}

void print(const char* label, const StatsDistance& d) {
    std::printf("%-34s", label);
    for (int m = 0; m < kMetricCount; ++m) std::printf(" %s=%.3g", metricName(static_cast<Metric>(m)), d.metric[m].value);
    std::printf("\n");
}

}  // namespace

TEST(StatsDistance, WassersteinOfAShiftedHistogramIsTheShift) {
    const TerrainStats s = statsOf(test::loadExemplarField("orom_rockies"));
    Histogram shifted = s.slope_deg.histogram;
    // Move all mass 8 bins (2 degrees) up; the top bins are empty for this DEM so nothing wraps.
    ASSERT_EQ(shifted.mass[shifted.mass.size() - 1], 0.0);
    for (size_t i = shifted.mass.size() - 1; i >= 8; --i) shifted.mass[i] = shifted.mass[i - 8];
    for (size_t i = 0; i < 8; ++i) shifted.mass[i] = 0.0;
    EXPECT_NEAR(wasserstein1(s.slope_deg.histogram, shifted), 2.0, 1e-9);
    EXPECT_NEAR(wasserstein1(shifted, s.slope_deg.histogram), 2.0, 1e-9);
    EXPECT_EQ(wasserstein1(s.slope_deg.histogram, s.slope_deg.histogram), 0.0);
    EXPECT_EQ(kolmogorovSmirnov(s.slope_deg.histogram, s.slope_deg.histogram), 0.0);
    EXPECT_GT(kolmogorovSmirnov(s.slope_deg.histogram, shifted), 0.0);

    // Two planes 10 and 25 degrees steep: W1 is the difference in degrees, KS is 1 (disjoint).
    auto plane = [](double degrees) {
        Heightfield f(64, 64, 30.0);
        const double g = std::tan(degrees * 3.14159265358979323846 / 180.0);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) f.at(x, y) = static_cast<float>(g * x * 30.0);
        return f;
    };
    const StatsDistance d = compareStats(statsOf(plane(10.0)), statsOf(plane(25.0)));
    EXPECT_NEAR(d[Metric::Slope].value, 15.0, 0.25);  // bins are 0.25 degrees wide
    EXPECT_EQ(d[Metric::Slope].ks, 1.0);
    // Drainage area is log-binned: its W1 is in decades.
    EXPECT_TRUE(s.drainage_area_m2.histogram.log_distance);
}

TEST(StatsDistance, SelfDistanceIsZeroAndDistancesAreSymmetric) {
    const TerrainStats a = statsOf(test::loadExemplarField("orom_alaska"));
    const TerrainStats b = statsOf(test::loadExemplarField("orom_appalachians"));
    const StatsDistance self = compareStats(a, a), ab = compareStats(a, b), ba = compareStats(b, a);
    for (int m = 0; m < kMetricCount; ++m) {
        EXPECT_EQ(self.metric[m].value, 0.0) << metricName(static_cast<Metric>(m));
        EXPECT_DOUBLE_EQ(ab.metric[m].value, ba.metric[m].value);
        EXPECT_DOUBLE_EQ(ab.metric[m].ks, ba.metric[m].ks);
    }
    EXPECT_GT(ab[Metric::Slope].value, 1.0);
}

TEST(StatsDistance, QuadrantsOfOneExemplarAreCloserThanDunesAreToEverest) {
    const Heightfield everest = test::loadExemplarField("orom_himalaya-everest");
    const Heightfield sahara = test::loadExemplarField("orom_sahara");
    const TerrainStats e0 = statsOf(quadrant(everest, 0)), e3 = statsOf(quadrant(everest, 3));
    const TerrainStats s0 = statsOf(quadrant(sahara, 0)), s3 = statsOf(quadrant(sahara, 3));
    const StatsDistance within_everest = compareStats(e0, e3), within_sahara = compareStats(s0, s3);
    const StatsDistance across = compareStats(e0, s3);
    print("everest q0 vs everest q3", within_everest);
    print("sahara q0 vs sahara q3", within_sahara);
    print("everest q0 vs sahara q3", across);
    for (Metric m : {Metric::Slope, Metric::ProfileCurvature, Metric::PlanCurvature, Metric::LocalRelief,
                     Metric::PitShare, Metric::DepressionShare, Metric::Landforms, Metric::SpectralSlope}) {
        EXPECT_LT(within_everest[m].value, across[m].value) << metricName(m);
        EXPECT_LT(within_sahara[m].value, across[m].value) << metricName(m);
        EXPECT_LT(within_everest[m].ks, across[m].ks) << metricName(m);
    }
}

TEST(StatsReference, SpreadOfRealPiecesJudgesRealAndFakeTerrain) {
    // Reference: Everest and Karakoram cut into 256^2 pieces (2x2 each at 648^2).
    const Heightfield everest = test::loadExemplarField("orom_himalaya-everest");
    const Heightfield karakoram = test::loadExemplarField("orom_karakoram");
    auto spread = referenceSpread({everest, karakoram}, 256);
    ASSERT_TRUE(spread) << spread.message();
    EXPECT_EQ(spread->pieces, 8);
    EXPECT_EQ(spread->pairs, 28);
    EXPECT_DOUBLE_EQ(spread->meters_per_pixel, everest.meters_per_pixel_x);
    for (int m = 0; m < kMetricCount; ++m) {
        EXPECT_LE(spread->median.metric[m].value, spread->max.metric[m].value);
        EXPECT_GT(spread->max.metric[m].value, 0.0) << metricName(static_cast<Metric>(m));
    }
    print("reference median", spread->median);
    print("reference max", spread->max);

    // Real high mountains not in the reference (Alaska) sit within the spread on most metrics...
    auto alaska = distanceToReference(test::loadExemplarField("orom_alaska"), *spread);
    ASSERT_TRUE(alaska) << alaska.message();
    const SpreadVerdict real = judgeAgainstSpread(*alaska, *spread);
    print("alaska to reference", *alaska);
    // ...while dunes and white noise are far outside on slope, relief and pits.
    auto dunes = distanceToReference(test::loadExemplarField("orom_sahara"), *spread);
    ASSERT_TRUE(dunes) << dunes.message();
    const SpreadVerdict fake = judgeAgainstSpread(*dunes, *spread);
    print("sahara to reference", *dunes);
    EXPECT_FALSE(fake.within);
    EXPECT_GT(fake.ratio[static_cast<int>(Metric::Slope)], 2.0);
    EXPECT_GT(fake.ratio[static_cast<int>(Metric::LocalRelief)], 2.0);
    EXPECT_LT(real.outside.size(), fake.outside.size());

    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(2000.0f, 6000.0f);
    Heightfield noise(512, 512, everest.meters_per_pixel_x);
    for (float& z : noise.heights) z = u(rng);
    auto noisy = distanceToReference(noise, *spread);
    ASSERT_TRUE(noisy) << noisy.message();
    const SpreadVerdict verdict = judgeAgainstSpread(*noisy, *spread);
    print("white noise to reference", *noisy);
    EXPECT_FALSE(verdict.within);
    EXPECT_GT(verdict.ratio[static_cast<int>(Metric::PitShare)], 10.0);
    EXPECT_GT(verdict.ratio[static_cast<int>(Metric::SpectralSlope)], 2.0);
}

TEST(StatsReference, CandidatesAreResampledToTheReferenceSpacing) {
    // St Helens at 10 m judged against a reference at 92.6 m: distanceToReference must resample it
    // (otherwise compareStats would reject the spacing mismatch).
    auto spread = referenceSpread({test::loadExemplarField("orom_rockies")}, 128);
    ASSERT_TRUE(spread) << spread.message();
    EXPECT_EQ(spread->pieces, 25);
    auto d = distanceToReference(test::loadExemplarField("glac_sthelens_10m"), *spread);
    ASSERT_TRUE(d) << d.message();
    EXPECT_TRUE(std::isfinite((*d)[Metric::Slope].value));
    // A coarser candidate is upsampled (100 px at 278 m become 300 px at 92.6 m); one that stays
    // below 32 px at the reference spacing is an error.
    Heightfield coarse = test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 100, 100);
    coarse.meters_per_pixel_x = coarse.meters_per_pixel_y = 92.6 * 3;
    auto upsampled = distanceToReference(coarse, *spread);
    EXPECT_TRUE(upsampled) << upsampled.message();
    auto too_small = distanceToReference(Heightfield(20, 20, 92.6), *spread);
    ASSERT_FALSE(too_small);
    EXPECT_NE(too_small.message().find("below 32x32"), std::string::npos) << too_small.message();
}

TEST(StatsDistanceDeathTest, DifferentSpacingIsAProgrammerError) {
    const TerrainStats a = statsOf(Heightfield(64, 64, 30.0, 1.0f));
    const TerrainStats b = statsOf(Heightfield(64, 64, 90.0, 1.0f));
    EXPECT_DEATH(compareStats(a, b), "same spacing");
}
