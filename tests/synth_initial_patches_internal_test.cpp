// Issue 16: the exemplars of the coarsest level's initial patches are drawn by systematic sampling
// over blocks of kInitialStrata^2 cells, so any block holds every exemplar in proportion to its
// area to within one cell, whatever the seed (independent draws left a 1024^2 synthesis, about
// nine cells, with one exemplar at 2.5% of the output and another at 56%).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/hash.h"
#include "synth/initial_patches.h"
#include "synth/reference_kernels.h"
#include "terrasynth/synthesizer.h"
#include "test_support.h"

namespace terrasynth::synth {
namespace {

constexpr int kCells = kInitialStrata * kInitialStrata;

TEST(InitialPatches, TheCellsOfABlockSampleTheRangeSystematically) {
    // The nine picks of a block, sorted, are one offset in [0, total / 9) plus j * total / 9.
    for (uint32_t total : {9u, 1000u, 648u * 648u, (1u << 31) - 1u})
        for (uint32_t seed = 1; seed <= 8; ++seed) {
            const uint32_t salt = core::levelSalt(seed, 4, 0);
            for (int by = -4; by < 4; ++by)
                for (int bx = -4; bx < 4; ++bx) {
                    std::vector<uint32_t> picks;
                    for (int j = 0; j < kCells; ++j) {
                        const int cx = bx * kInitialStrata + j % kInitialStrata, cy = by * kInitialStrata + j / kInitialStrata;
                        picks.push_back(stratifiedPick(cx, cy, salt, total));
                        ASSERT_LT(picks.back(), total);
                    }
                    std::sort(picks.begin(), picks.end());
                    const double step = static_cast<double>(total) / kCells;
                    ASSERT_LT(picks[0], step + 1.0) << "block " << bx << "," << by << " total " << total;
                    for (int j = 1; j < kCells; ++j)
                        ASSERT_NEAR(static_cast<double>(picks[j]) - picks[0], j * step, 1.0)
                            << "block " << bx << "," << by << " total " << total;
                }
        }
}

TEST(InitialPatches, EveryBlockHoldsTheDefaultExemplarsInProportionToTheirArea) {
    // The four default exemplars are equally large: every block of nine cells holds two or three
    // patches of each, and over many blocks the picks are not always the same cells (the order
    // within a block is random).
    auto db = test::defaultDatabase();
    ASSERT_TRUE(db);
    const int level = automaticCoarsestLevel(*db);
    const std::vector<uint32_t> cumulative = cumulativeInteriorAreas(db->levels[level]);
    ASSERT_EQ(cumulative.size(), 4u);
    std::vector<int> first_cell_counts(4, 0);
    for (uint32_t seed = 1; seed <= 20; ++seed) {
        const uint32_t salt = core::levelSalt(seed, level, 0);
        for (int by = -3; by < 3; ++by)
            for (int bx = -3; bx < 3; ++bx) {
                std::vector<int> count(4, 0);
                for (int j = 0; j < kCells; ++j) {
                    const uint32_t pick = stratifiedPick(bx * kInitialStrata + j % kInitialStrata,
                                                         by * kInitialStrata + j / kInitialStrata, salt, cumulative.back());
                    size_t e = 0;
                    while (e + 1 < cumulative.size() && pick >= cumulative[e]) ++e;
                    ++count[e];
                    if (j == 0) ++first_cell_counts[e];
                }
                for (int e = 0; e < 4; ++e) {
                    EXPECT_GE(count[e], 2) << "seed " << seed << " block " << bx << "," << by;
                    EXPECT_LE(count[e], 3) << "seed " << seed << " block " << bx << "," << by;
                }
            }
    }
    for (int e = 0; e < 4; ++e) EXPECT_GT(first_cell_counts[e], 720 / 8) << "exemplar " << e;  // of 720 blocks, about 180 each
}

}  // namespace
}  // namespace terrasynth::synth
