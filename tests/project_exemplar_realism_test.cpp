// Realism of one-exemplar syntheses (issues 16 and 17): the synthesis draws from the whole
// exemplar, not only its flattest part; its slope, curvature and landforms sit within the
// exemplar's own spread; drainage (Drainage::Breach, the default) leaves fewer closed
// depressions than no drainage; and a multi-exemplar database uses its exemplars in proportion to their size.
// Yardstick: referenceSpread of the exemplar itself (how far its own 256^2 pieces are from each
// other), as project_realism_test does.
//
// CI size: 512^2, one seed, the exemplars that showed the collapse of issue 16 (wn_mackay,
// wn_big_butte: valley floors or plain around relief, 30 m), the smoothest and a rough default
// exemplar (orom_appalachians, orom_rockies) and a 30 m fluvial one (ttb_bigtujunga); drainage on
// all 14 fluvial exemplars. Every shared exemplar at 1024^2 and several seeds, with the steering
// instrument, is scripts/realism/realism_survey.py (docs/realism.md has its figures).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <utility>

#include "terrasynth/source_usage.h"
#include "terrasynth/synthesizer.h"
#include "terrasynth/terrain_stats.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

constexpr int kSize = 512;
constexpr uint32_t kSeed = 3;

const char* const kExemplars[] = {"wn_mackay", "wn_big_butte", "orom_appalachians", "orom_rockies", "ttb_bigtujunga"};
// Issue 17's exemplars: every shared one but the dune fields and karst, whose closed depressions are real.
const char* const kFluvial[] = {"glac_mtperdu_20m", "glac_sthelens_10m", "orom_alaska", "orom_andes-chile",
                                "orom_appalachians", "orom_highlands", "orom_himalaya-everest", "orom_karakoram",
                                "orom_norway", "orom_rockies", "osge_mt_fuji_90m", "ttb_bigtujunga",
                                "wn_big_butte", "wn_mackay"};

// One-exemplar database, cached in the build tree (rebuilt when the exemplar or options change).
std::shared_ptr<const ExemplarDatabase> database(const std::string& stem) {
    auto db = loadOrBuildDatabase({test::sharedExemplarsDir() + "/" + stem + ".png"}, DatabaseBuildOptions{},
                                  test::tmpPath("exemplar_" + stem + ".tsdb"));
    EXPECT_TRUE(db) << stem << ": " << db.message();
    return db ? db.value() : nullptr;
}

// An exemplar at the database spacing (level 0 of its atlas).
Heightfield exemplarField(const ExemplarDatabase& db, int exemplar = 0) {
    const DatabaseLevel& l = db.levels[0];
    const AtlasRect& r = l.rects[exemplar];
    Heightfield f(r.width, r.height, db.meters_per_pixel);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) f.at(x, y) = l.height_m[static_cast<size_t>(r.y + y) * l.width + r.x + x];
    return f;
}

struct Judged {
    double flattest_share = NAN;
    SpreadVerdict verdict;
    StatsDistance distance;
    double ratio(Metric m) const { return verdict.ratio[static_cast<int>(m)]; }
};

Judged synthesizeAndJudge(const std::string& stem, Drainage drainage, bool relax_offsets) {
    Judged j;
    auto db = database(stem);
    if (!db) return j;
    auto synthesizer = Synthesizer::create(db);
    EXPECT_TRUE(synthesizer) << synthesizer.message();
    if (!synthesizer) return j;
    SynthesisParams params;
    params.seed = kSeed;
    params.drainage = drainage;
    params.relax_offsets = relax_offsets;
    auto out = synthesizer.value()->synthesize({0, 0, kSize, kSize}, params, 0, true);
    EXPECT_TRUE(out) << out.message();
    if (!out) return j;
    const Heightfield exemplar = exemplarField(*db);
    auto usage = measureSourceUsage({exemplar}, out->source_x, out->source_y, out->source_exemplar);
    EXPECT_TRUE(usage) << usage.message();
    static std::map<std::string, ReferenceSpread> spreads;
    if (!spreads.count(stem)) {
        auto spread = referenceSpread({exemplar}, 256);
        EXPECT_TRUE(spread) << stem << ": " << spread.message();
        if (!spread) return j;
        spreads[stem] = std::move(spread.value());
    }
    auto distance = distanceToReference(out->heights, spreads[stem]);
    EXPECT_TRUE(distance) << distance.message();
    if (!usage || !distance) return j;
    j.flattest_share = usage.value()[0].flattest_share;
    j.distance = distance.value();
    j.verdict = judgeAgainstSpread(j.distance, spreads[stem]);
    std::printf("%-18s %-6s %-7s flattest30 %5.1f%%", stem.c_str(), drainage == Drainage::Off ? "off" : "breach",
                relax_offsets ? "relaxed" : "paper",
                100.0 * j.flattest_share);
    for (Metric m : {Metric::Slope, Metric::ProfileCurvature, Metric::Landforms, Metric::DrainageArea,
                     Metric::DepressionShare})
        std::printf("  %s %.2f", metricName(m), j.ratio(m));
    std::printf("  (depressions %.4f)\n", j.distance[Metric::DepressionShare].value);
    return j;
}

// relax_offsets: SynthesisParams::relax_offsets, the default unless given.
const Judged& judged(const std::string& stem, Drainage drainage, bool relax_offsets = SynthesisParams{}.relax_offsets) {
    static std::map<std::tuple<std::string, int, bool>, Judged> results;
    const auto key = std::make_tuple(stem, static_cast<int>(drainage), relax_offsets);
    if (!results.count(key)) results[key] = synthesizeAndJudge(stem, drainage, relax_offsets);
    return results[key];
}

}  // namespace

TEST(ExemplarRealism, EveryExemplarAloneDrawsFromAllOfIt) {
    // Issue 16: an unbiased synthesis draws about 30% of its pixels from the exemplar's flattest 30%
    // (by 9x9 local relief), the goal is 20-45%; before, mixed exemplars collapsed onto their valley
    // floors (wn_mackay 100%). Slope, profile curvature and landforms stay within the exemplar's own
    // spread. Without drainage, as issue 16 measured, and with the default settings (breach).
    for (const char* stem : kExemplars)
        for (Drainage drainage : {Drainage::Off, SynthesisParams{}.drainage}) {
            const Judged& j = judged(stem, drainage);
            const char* with = drainage == Drainage::Off ? " off" : " breach";
            EXPECT_GE(j.flattest_share, 0.20) << stem << with;
            EXPECT_LE(j.flattest_share, 0.45) << stem << with;
            for (Metric m : {Metric::Slope, Metric::ProfileCurvature, Metric::Landforms})
                EXPECT_LE(j.ratio(m), 1.0) << stem << with << " " << metricName(m);
        }
}

TEST(ExemplarRealism, BreachingLeavesFewerClosedDepressions) {
    // Issue 17, on every fluvial shared exemplar (512^2, seed 3): with drainage (Drainage::Breach,
    // the default) the drainage area stays within the exemplar's own spread, slope, profile
    // curvature and landforms stay the exemplar's (below), and the share of
    // pixels in closed depressions either does too or is at most half as far from the exemplar's as
    // without drainage (measured: within the spread for 10 of 14; orom_appalachians, highlands,
    // himalaya-everest and wn_mackay lose 56-78% of their distance). Together the 14 lose at least
    // half of it (measured: 70%). orom_andes-chile, whose depressions are within the spread either
    // way, comes out 0.55 points further than off. (With no breach at level 0, wn_big_butte lost 49%.)
    // The steering instrument's figures at 1024^2 and six seeds are in docs/realism.md.
    double total_on = 0.0, total_off = 0.0;
    for (const char* stem : kFluvial) {
        const Judged& on = judged(stem, Drainage::Breach);
        const Judged& off = judged(stem, Drainage::Off);
        const double on_distance = on.distance[Metric::DepressionShare].value;
        const double off_distance = off.distance[Metric::DepressionShare].value;
        EXPECT_TRUE(on.ratio(Metric::DepressionShare) <= 1.0 || on_distance <= 0.5 * off_distance)
            << stem << ": depressions " << on_distance << " from the exemplar's share with breach, " << off_distance
            << " without; spread ratio " << on.ratio(Metric::DepressionShare);
        EXPECT_LE(on.ratio(Metric::DrainageArea), 1.0) << stem;
        // Drainage carves channels, not the terrain's character: slope, profile curvature and
        // landforms stay within the exemplar's spread, or at most 10% further out than without
        // drainage (orom_andes-chile's slope and curvature are outside it either way at 512^2,
        // 1.06 and 1.26 of the spread off, 1.09 and 1.26 with breach).
        for (Metric m : {Metric::Slope, Metric::ProfileCurvature, Metric::Landforms})
            EXPECT_LE(on.ratio(m), std::max(1.0, 1.1 * off.ratio(m))) << stem << " with breach: " << metricName(m);
        total_on += on_distance;
        total_off += off_distance;
    }
    EXPECT_LT(total_on, 0.5 * total_off);
}

TEST(ExemplarRealism, NoExemplarPixelIsStretchedOverItsNeighbours) {
    // A coherent patch that runs into its exemplar's interior edge continues with another candidate;
    // moving the edge's candidates onto the edge row (as before) repeated that row or column over
    // many pixels, a fixed point of the passes that showed as striped blocks on exemplars barely
    // taller than a patch. Measured at the coarsest level of ttb_bigtujunga alone (36 px tall inside
    // there), 128^2, seeds 3-5: neighbours drawn from the same exemplar pixel 3.1-3.5% before,
    // at most 0.03% now; a coherent patch never repeats one.
    auto db = database("ttb_bigtujunga");
    ASSERT_TRUE(db);
    auto synthesizer = Synthesizer::create(db);
    ASSERT_TRUE(synthesizer) << synthesizer.message();
    for (uint32_t seed : {3u, 4u, 5u}) {
        SynthesisParams params;
        params.seed = seed;
        const int level = coarsestSynthesizedLevel(*db, params);
        auto out = synthesizer.value()->synthesize({0, 0, 128, 128}, params, level, true);
        ASSERT_TRUE(out) << out.message();
        size_t repeated = 0, pairs = 0;
        auto same = [&](size_t a, size_t b) {
            return out->source_exemplar[a] == out->source_exemplar[b] && out->source_x[a] == out->source_x[b] &&
                   out->source_y[a] == out->source_y[b];
        };
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) {
                const size_t i = static_cast<size_t>(y) * 128 + x;
                if (x + 1 < 128) repeated += same(i, i + 1), ++pairs;
                if (y + 1 < 128) repeated += same(i, i + 128), ++pairs;
            }
        const double share = static_cast<double>(repeated) / pairs;
        std::printf("seed %u, level %d: %.3f%% of neighbours drawn from the same exemplar pixel\n", seed, level, 100.0 * share);
        EXPECT_LE(share, 0.005) << "seed " << seed;
    }
}

// Per seed, each exemplar's share of a 1024^2 synthesis at the origin (one share block) against its
// share of the database; returns how many (exemplar, seed) pairs fall outside a factor 2, and
// expects none outside a factor `worst`.
namespace {

int sharesOutsideFactor2(const std::shared_ptr<const ExemplarDatabase>& db, uint32_t seeds, double worst) {
    auto synthesizer = Synthesizer::create(db);
    EXPECT_TRUE(synthesizer) << synthesizer.message();
    if (!synthesizer) return -1;
    std::vector<Heightfield> exemplars;
    for (int e = 0; e < static_cast<int>(db->exemplars.size()); ++e) exemplars.push_back(exemplarField(*db, e));
    int outside = 0;
    for (uint32_t seed = 1; seed <= seeds; ++seed) {
        SynthesisParams params;
        params.seed = seed;
        auto out = synthesizer.value()->synthesize({0, 0, 1024, 1024}, params, 0, true);
        EXPECT_TRUE(out) << out.message();
        if (!out) return -1;
        auto usage = measureSourceUsage(exemplars, out->source_x, out->source_y, out->source_exemplar);
        EXPECT_TRUE(usage) << usage.message();
        if (!usage) return -1;
        std::printf("seed %2u:", seed);
        for (size_t e = 0; e < usage->size(); ++e) {
            const ExemplarUsage& u = (*usage)[e];
            const double ratio = u.output_share / u.exemplar_share;
            std::printf(" %s %.1f%% (database %.1f%%)%s", db->exemplars[e].name.c_str(), 100 * u.output_share,
                        100 * u.exemplar_share, ratio < 0.5 || ratio > 2 ? " !" : "");
            EXPECT_GE(ratio, 1 / worst) << db->exemplars[e].name << " seed " << seed;
            EXPECT_LE(ratio, worst) << db->exemplars[e].name << " seed " << seed;
            outside += ratio < 0.5 || ratio > 2;
        }
        std::printf("\n");
    }
    return outside;
}

}  // namespace

TEST(ExemplarRealism, ExemplarsShareTheOutputInProportionToTheirSize) {
    // Issue 16: without type painting, each exemplar's share of the output within a factor 2 of its
    // share of the database. Before: orom_appalachians, the smoothest default exemplar, took 82%;
    // with a draw per initial patch, a 1024^2 synthesis held about nine patches, and 30 of 51
    // (exemplar, seed) pairs of the 17 shared exemplars fell outside. With share blocks
    // (synth/initial_patches.h) the four default exemplars take 22.7-27.7% each over seeds 1-10,
    // and the 17 keep 0.56-1.43 of their shares over seeds 1-3 (docs/realism.md, "Share blocks").
    EXPECT_EQ(sharesOutsideFactor2(test::defaultDatabase(), 10, 1.5), 0);
    EXPECT_EQ(sharesOutsideFactor2(test::sharedDatabase(), 3, 2.0), 0);
}
