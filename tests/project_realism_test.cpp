// Realism of synthesized terrain judged as a geomorphologist would (docs/realism.md): slope,
// curvature, relief, drainage and spectrum of the synthesis against the spread between pieces of
// the real exemplars it draws from.
#include <gtest/gtest.h>

#include <cmath>

#include "terrasynth/synthesizer.h"
#include "terrasynth/terrain_stats.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

struct Judged {
    SpreadVerdict verdict;
    StatsDistance distance;
};

const ReferenceSpread& exemplarSpread() {
    static ReferenceSpread spread = [] {
        std::vector<Heightfield> exemplars;
        for (const char* stem : {"orom_alaska", "orom_appalachians", "orom_himalaya-everest", "orom_rockies"})
            exemplars.push_back(test::loadExemplarField(stem));
        auto s = referenceSpread(exemplars, 256);
        EXPECT_TRUE(s) << s.message();
        return s.value();
    }();
    return spread;
}

Judged judge(const Heightfield& terrain) {
    auto d = distanceToReference(terrain, exemplarSpread());
    EXPECT_TRUE(d) << d.message();
    Judged j{judgeAgainstSpread(d.value(), exemplarSpread()), d.value()};
    for (int m = 0; m < kMetricCount; ++m)
        std::printf("  %-18s distance %10.4g  ratio to exemplar spread %.2f\n", metricName(static_cast<Metric>(m)),
                    d->metric[m].value, j.verdict.ratio[m]);
    return j;
}

}  // namespace

TEST(Realism, SynthesizedTerrainStaysWithinTheExemplarSpread) {
    SynthesizerOptions options;
    auto synthesizer = Synthesizer::create(test::defaultDatabase(), options);
    ASSERT_TRUE(synthesizer) << synthesizer.message();
    for (uint32_t seed : {1u, 2u}) {
        SynthesisParams params;
        params.seed = seed;
        auto out = synthesizer.value()->synthesize({0, 0, 512, 512}, params, 0, false);
        ASSERT_TRUE(out) << out.message();
        std::printf("seed %u vs the four default exemplars (256^2 pieces):\n", seed);
        const Judged j = judge(out->heights);
        // The distributions that carry the look of a terrain must be as close to the exemplars as
        // two pieces of real terrain are to each other.
        // Depression share is not asserted: pixel-based synthesis has no notion of drainage (paper
        // s6 limitations) and leaves 2-3x the exemplars' spread of closed depressions; see the issue note.
        for (Metric m : {Metric::Slope, Metric::ProfileCurvature, Metric::PlanCurvature, Metric::LocalRelief,
                         Metric::DrainageArea, Metric::Landforms, Metric::SpectralSlope, Metric::PitShare})
            EXPECT_LE(j.verdict.ratio[static_cast<int>(m)], 1.0) << metricName(m) << " seed " << seed;
    }
}

TEST(Realism, NoiseIsJudgedUnrealisticByTheSameYardstick) {
    // The yardstick must be able to fail: white noise with the exemplars' relief is far outside.
    Heightfield noise(512, 512, test::defaultDatabase()->meters_per_pixel);
    uint32_t state = 12345;
    for (float& h : noise.heights) {
        state = state * 1664525u + 1013904223u;
        h = 1500.0f + 800.0f * static_cast<float>(state >> 8) / 16777216.0f;
    }
    const Judged j = judge(noise);
    EXPECT_GT(j.verdict.ratio[static_cast<int>(Metric::PitShare)], 1.0);
    EXPECT_GT(j.verdict.ratio[static_cast<int>(Metric::SpectralSlope)], 1.0);
}
