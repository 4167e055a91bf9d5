// Issue 16: the coarsest level's exemplars come from share blocks (synth/initial_patches.h): every
// block of the world grid holds every exemplar in proportion to its area, each as one compact
// region, whatever the seed (a draw per initial patch left a 1024^2 synthesis, about nine patches,
// with at most nine exemplars of a 17-exemplar database).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/hash.h"
#include "synth/initial_patches.h"
#include "test_support.h"

namespace terrasynth::synth {
namespace {

// The 4-connected regions of exemplar e's cells in one block.
int regions(const uint8_t* cells, int e) {
    std::vector<uint8_t> seen(kShareCellsPerBlock, 0);
    int count = 0;
    for (int first = 0; first < kShareCellsPerBlock; ++first) {
        if (cells[first] != e || seen[first]) continue;
        ++count;
        std::vector<int> stack{first};
        seen[first] = 1;
        while (!stack.empty()) {
            const int c = stack.back();
            stack.pop_back();
            const int x = c % kShareCellsPerSide, y = c / kShareCellsPerSide;
            const int next[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
            for (const auto& n : next) {
                if (n[0] < 0 || n[1] < 0 || n[0] >= kShareCellsPerSide || n[1] >= kShareCellsPerSide) continue;
                const int k = n[1] * kShareCellsPerSide + n[0];
                if (!seen[k] && cells[k] == e) seen[k] = 1, stack.push_back(k);
            }
        }
    }
    return count;
}

void expectProportionalCompactBlocks(const std::vector<uint64_t>& weights, uint32_t seeds) {
    double total = 0;
    for (uint64_t w : weights) total += static_cast<double>(w);
    for (uint32_t seed = 1; seed <= seeds; ++seed) {
        const uint32_t salt = core::levelSalt(seed, 4, 0);
        const std::vector<uint8_t> map = shareCellExemplars(weights, std::vector<uint8_t>(weights.size(), 1), salt, -3, -2, 6, 5);
        ASSERT_EQ(map.size(), 30u * kShareCellsPerBlock);
        for (int b = 0; b < 30; ++b) {
            const uint8_t* cells = &map[static_cast<size_t>(b) * kShareCellsPerBlock];
            std::vector<int> count(weights.size(), 0);
            int split = 0;
            for (int c = 0; c < kShareCellsPerBlock; ++c) {
                ASSERT_LT(cells[c], weights.size());
                ++count[cells[c]];
            }
            for (size_t e = 0; e < weights.size(); ++e) {
                const double quota = kShareCellsPerBlock * static_cast<double>(weights[e]) / total;
                EXPECT_GE(count[e], std::floor(quota) - 1e-9) << "seed " << seed << " block " << b << " exemplar " << e;
                EXPECT_LE(count[e], std::ceil(quota) + 1e-9) << "seed " << seed << " block " << b << " exemplar " << e;
                // One region each, but for the run that wraps around the curve's end: at most two.
                const int pieces = regions(cells, static_cast<int>(e));
                EXPECT_LE(pieces, 2) << "exemplar " << e << ": seed " << seed << " block " << b;
                split += pieces > 1;
            }
            EXPECT_LE(split, 1) << "seed " << seed << " block " << b;
        }
    }
}

TEST(ShareBlocks, EveryBlockHoldsEveryExemplarInProportionAsCompactRegions) {
    // Equal weights (the default project), the 17 shared exemplars' level-0 areas at 92.6 m (five
    // hold under 2%), and weights large enough to need scaling; a zero weight (an exemplar never
    // used) never appears.
    expectProportionalCompactBlocks({648u * 648u, 648u * 648u, 648u * 648u, 648u * 648u}, 6);
    expectProportionalCompactBlocks({110u * 110u, 78u * 78u, 648u * 648u, 648u * 648u, 648u * 648u, 648u * 648u,
                                     648u * 648u, 648u * 648u, 648u * 648u, 648u * 648u, 648u * 648u, 648u * 648u,
                                     648u * 648u, 1086u * 1086u, 97u * 97u, 68u * 68u, 90u * 90u},
                                    6);
    expectProportionalCompactBlocks({uint64_t(3) << 40, uint64_t(1) << 40, 0, uint64_t(5) << 38}, 6);
}

TEST(ShareBlocks, OrderAndShapeChangeWithTheBlockAndTheSeed) {
    // The exemplar at a block's first cell and the shape of a region differ between blocks and
    // seeds: the layout is no fixed pattern repeated over the world.
    const std::vector<uint64_t> weights(4, 1000);
    std::vector<int> corner(4, 0);
    int blocks = 0;
    for (uint32_t seed = 1; seed <= 10; ++seed) {
        const std::vector<uint8_t> map = shareCellExemplars(weights, {1, 1, 1, 1}, shareSalt(seed), -4, -4, 8, 8);
        for (size_t b = 0; b < 64; ++b, ++blocks) ++corner[map[b * kShareCellsPerBlock]];
    }
    for (int e = 0; e < 4; ++e) EXPECT_GT(corner[e], blocks / 8) << "exemplar " << e;  // about a quarter each
}

TEST(ShareBlocks, AWindowGetsTheSameCellsAsTheWholeGrid) {
    const std::vector<uint64_t> weights = {5, 7, 11};
    const uint32_t salt = core::levelSalt(9, 3, 0);
    const std::vector<uint8_t> whole = shareCellExemplars(weights, {1, 1, 1}, salt, -2, -2, 5, 5);
    const std::vector<uint8_t> part = shareCellExemplars(weights, {1, 1, 1}, salt, 1, 0, 2, 1);
    for (int i = 0; i < 2; ++i)
        for (int c = 0; c < kShareCellsPerBlock; ++c)
            ASSERT_EQ(part[static_cast<size_t>(i) * kShareCellsPerBlock + c],
                      whole[(static_cast<size_t>(2) * 5 + 3 + i) * kShareCellsPerBlock + c]);
}

TEST(ShareBlocks, ABlockIsA1024SquareOfLevelZero) {
    EXPECT_EQ(shareBlockSide(0), 1024);
    EXPECT_EQ(shareBlockSide(4), 64);
    EXPECT_EQ(shareBlockSide(6), 16);
    EXPECT_EQ(shareBlockSide(9), 16);
}

TEST(ShareBlocks, AnExemplarNotEnteredYetLendsItsCellsToItsNeighbourOnTheCurve) {
    // Before a small exemplar enters, its cells show another exemplar; every shown exemplar is still
    // one region (two where the curve wraps); once it enters, it gets exactly those cells back and
    // nothing else changes.
    const std::vector<uint64_t> weights = {648u * 648u, 110u * 110u, 648u * 648u, 68u * 68u, 1086u * 1086u};
    const std::vector<uint8_t> all = {1, 1, 1, 1, 1}, large = {1, 0, 1, 0, 1};
    for (uint32_t seed = 1; seed <= 12; ++seed) {
        const std::vector<uint8_t> before = shareCellExemplars(weights, large, shareSalt(seed), -2, -2, 4, 4);
        const std::vector<uint8_t> after = shareCellExemplars(weights, all, shareSalt(seed), -2, -2, 4, 4);
        for (size_t c = 0; c < after.size(); ++c) {
            ASSERT_TRUE(large[before[c]]) << "cell " << c;
            if (large[after[c]]) {
                ASSERT_EQ(before[c], after[c]) << "cell " << c;
            }
        }
        for (int b = 0; b < 16; ++b)
            for (int e : {0, 2, 4}) {
                const uint8_t* cells = &before[static_cast<size_t>(b) * kShareCellsPerBlock];
                const int count = static_cast<int>(std::count(cells, cells + kShareCellsPerBlock, e));
                ASSERT_GT(count, 0);
                EXPECT_LE(regions(cells, e), 2) << "seed " << seed << " block " << b << " exemplar " << e;
            }
    }
}

TEST(ShareBlocks, ExemplarsEnterWhereTheyAreLargeEnough) {
    // The default exemplars are all large enough at the automatic coarsest level; at a level where
    // none is, each enters there if it has interior pixels to copy.
    auto db = test::defaultDatabase();
    ASSERT_TRUE(db);
    const int level = automaticCoarsestLevel(*db);
    for (int entry : entryLevels(*db, level)) EXPECT_EQ(entry, level);
    const int top = db->levelCount() - 1;
    ASSERT_LT(db->levels[top].rects[0].width, kMinCoarsestSide);
    const std::vector<int> entries = entryLevels(*db, top);
    for (size_t e = 0; e < entries.size(); ++e) {
        const AtlasRect& r = db->levels[top].rects[e];
        EXPECT_EQ(entries[e], r.width > 2 * kInteriorMargin && r.height > 2 * kInteriorMargin ? top : entries[e] < 0 ? -1 : top - 1)
            << "exemplar " << e;
        EXPECT_GE(entries[e], top - 1);
    }
}

}  // namespace
}  // namespace terrasynth::synth
