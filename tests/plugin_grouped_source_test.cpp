// groupedSource / tileGroupedSource (terrasynth_plugin/height_source.h) over the shipped project's
// synthesized terrain: tiles cut from their group's synthesis are the terrain's own samples, the
// terrain is asked once per group, and what does not fit a group goes through untouched.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "terrasynth/terrain.h"
#include "terrasynth_plugin/height_source.h"
#include "test_support.h"

namespace terrasynth::plugin {
namespace {

std::shared_ptr<Terrain> shippedTerrain() {
    static std::shared_ptr<Terrain> terrain = [] {
        auto t = Terrain::open(test::dataDir() + "/default.tsyn");
        EXPECT_TRUE(t) << t.message();
        return t ? *t : nullptr;
    }();
    return terrain;
}

// The terrain's heights, recording every window asked.
struct CountingSource {
    std::shared_ptr<Terrain> terrain = shippedTerrain();
    std::mutex mutex;
    std::vector<std::pair<PixelWindow, int>> asked;  // window, level
    int largest_allowed = 1 << 30;  // larger windows fail, as a group might

    HeightSource source() {
        return [this](const PixelWindow& w, int level) -> Result<Heightfield> {
            {
                std::lock_guard<std::mutex> lock(mutex);
                asked.emplace_back(w, level);
            }
            if (w.width > largest_allowed) return Status::error("window too large for this test's source");
            return terrain->heights(w, level);
        };
    }
    size_t count(const PixelWindow& w, int level = 0) {
        std::lock_guard<std::mutex> lock(mutex);
        return static_cast<size_t>(std::count(asked.begin(), asked.end(), std::make_pair(w, level)));
    }
};

bool sameBits(const Heightfield& a, const Heightfield& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.heights.data(), b.heights.data(), a.heights.size() * sizeof(float)) == 0;
}

// A 32-quad tile's read window with the tile builder's apron of one sample (mesh step 1).
PixelWindow tileWindow(int64_t tx, int64_t ty) { return {tx * 32 - 1, ty * 32 - 1, 35, 35}; }
// Groups of 4 x 4 such tiles: 128 samples plus 8 on every side.
PixelWindow groupWindow(int64_t gx, int64_t gy) { return {gx * 128 - 8, gy * 128 - 8, 145, 145}; }

TEST(GroupedSource, TilesAreTheTerrainsOwnSamplesAndEachGroupIsSynthesizedOnce) {
    CountingSource counting;
    ASSERT_TRUE(counting.terrain);
    const HeightSource grouped = tileGroupedSource(counting.source(), 32);
    // Tiles 2..5 along each axis: the four groups around the origin's (1, 1) corner; then the
    // parent-level reads the tile builder makes (half the tile plus one sample, at level 1).
    for (int pass = 0; pass < 2; ++pass)
        for (int64_t ty = 2; ty < 6; ++ty)
            for (int64_t tx = 2; tx < 6; ++tx) {
                const PixelWindow w = tileWindow(tx, ty);
                auto cut = grouped(w, 0);
                auto own = counting.terrain->heights(w, 0);
                ASSERT_TRUE(cut && own) << (cut ? own.message() : cut.message());
                EXPECT_TRUE(sameBits(*cut, *own)) << "tile " << tx << ", " << ty;
            }
    for (int64_t gy : {0, 1})
        for (int64_t gx : {0, 1}) EXPECT_EQ(counting.count(groupWindow(gx, gy)), 1u) << gx << ", " << gy;
    EXPECT_EQ(counting.count(tileWindow(3, 3)), 0u);  // no tile was asked of the terrain itself
    const PixelWindow parent{2 * 16, 3 * 16, 17, 17};
    auto cut = grouped(parent, 1), own = counting.terrain->heights(parent, 1);
    ASSERT_TRUE(cut && own);
    EXPECT_TRUE(sameBits(*cut, *own));
    EXPECT_EQ(counting.count(groupWindow(0, 0), 1), 1u);  // level 1 has groups of its own
    EXPECT_EQ(counting.count(groupWindow(0, 0), 0), 1u);
}

TEST(GroupedSource, WindowsThatFitNoGroupGoToTheSourceAsTheyAre) {
    CountingSource counting;
    const HeightSource grouped = tileGroupedSource(counting.source(), 32);
    // Across the border of groups 0 and 1 (their padded windows end at 137 and start at 120).
    const PixelWindow across{110, 0, 35, 35}, small{10, 10, 4, 4}, wide{-8, -8, 200, 100};
    for (const PixelWindow& w : {across, small, wide}) {
        auto cut = grouped(w, 0);
        ASSERT_TRUE(cut) << cut.message();
        EXPECT_EQ(counting.count(w), 1u) << w.x << ", " << w.y << " " << w.width << "x" << w.height;
    }
    EXPECT_EQ(counting.asked.size(), 3u);
}

TEST(GroupedSource, ThreadsAskingForOneGroupWaitForOneSynthesis) {
    CountingSource counting;
    const HeightSource grouped = tileGroupedSource(counting.source(), 32);
    std::atomic<int> failures{0};
    std::vector<std::thread> threads;
    for (int i = 0; i < 4; ++i)
        threads.emplace_back([&, i] { failures += !grouped(tileWindow(8 + i % 2, 8 + i / 2), 0); });
    for (auto& t : threads) t.join();
    EXPECT_EQ(failures.load(), 0);
    EXPECT_EQ(counting.count(groupWindow(2, 2)), 1u);
    EXPECT_EQ(counting.asked.size(), 1u);
}

TEST(GroupedSource, AFailedGroupLeavesTheTileToTheSource) {
    CountingSource counting;
    counting.largest_allowed = 64;  // every group fails, tiles do not
    const HeightSource grouped = tileGroupedSource(counting.source(), 32);
    const PixelWindow w = tileWindow(-3, 1);
    auto cut = grouped(w, 0);
    ASSERT_TRUE(cut) << cut.message();
    auto own = counting.terrain->heights(w, 0);
    ASSERT_TRUE(own);
    EXPECT_TRUE(sameBits(*cut, *own));
    EXPECT_EQ(counting.count(groupWindow(-1, 0)), 1u);
    EXPECT_EQ(counting.count(w), 1u);
}

}  // namespace
}  // namespace terrasynth::plugin
