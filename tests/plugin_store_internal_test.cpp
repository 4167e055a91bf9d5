// The resident tiles' registry and its unloader policy: every byte a tile holds is counted (its
// render arrays and its data's samples), and eviction takes the least recently used tiles, the
// finest first among equals, never one the last cull used, and only until the budget holds.
#include <gtest/gtest.h>

#include <osg/Group>

#include "tile_store.h"

namespace terrasynth::plugin {
namespace {

// A build holding `render_bytes` of geometry and a data model of samples x samples heights.
TileBuild fakeBuild(const TileKey& key, size_t render_bytes, int samples) {
    TileBuild build;
    build.key = key;
    auto data = std::make_shared<TileData>();
    data->key = key;
    data->heights = Heightfield(samples, samples, 1.0);
    build.data = data;
    build.node = new osg::Group;
    build.bytes = render_bytes;
    return build;
}

TEST(PluginStore, CountsEveryResidentByte) {
    TileStore store;
    const TileKey a{0, 0, 0}, b{1, 0, 0};
    const ResidentTile& first = store.add(fakeBuild(a, 1000, 10), 5);
    EXPECT_EQ(first.bytes, size_t(1000 + 10 * 10 * sizeof(float)));
    EXPECT_EQ(first.last_used_frame, 5u);
    store.add(fakeBuild(b, 500, 5), 6);
    EXPECT_EQ(store.size(), 2u);
    EXPECT_EQ(store.bytes(), size_t(1000 + 400 + 500 + 100));
    // A rebuild replaces the content and hands back the node it drew.
    ResidentTile* tile = store.find(a);
    ASSERT_NE(tile, nullptr);
    const osg::ref_ptr<osg::Node> before = tile->node;
    TileBuild rebuild = fakeBuild(a, 100, 10);
    rebuild.generation = 7;
    const osg::Node* after = rebuild.node.get();
    EXPECT_EQ(store.replace(*tile, std::move(rebuild)).get(), before.get());
    EXPECT_EQ(tile->node.get(), after);
    EXPECT_EQ(tile->generation, 7u);
    EXPECT_EQ(store.bytes(), size_t(100 + 400 + 500 + 100));
    EXPECT_EQ(store.remove(b).get() != nullptr, true);
    EXPECT_EQ(store.find(b), nullptr);
    EXPECT_EQ(store.bytes(), size_t(100 + 400));
    EXPECT_EQ(store.size(), 1u);
}

TEST(PluginStore, EvictsLeastRecentlyUsedFinestFirstUntilTheBudgetHolds) {
    TileStore store;
    // 1000 bytes each; last used in frames 1, 1, 2, 3 and 9 (the last cull's frame).
    const TileKey coarse_old{2, 0, 0}, fine_old{0, 0, 0}, middle{1, 0, 0}, recent{0, 1, 0}, drawn{0, 2, 0};
    store.add(fakeBuild(coarse_old, 1000, 0), 1);
    store.add(fakeBuild(fine_old, 1000, 0), 1);
    store.add(fakeBuild(middle, 1000, 0), 2);
    store.add(fakeBuild(recent, 1000, 0), 3);
    store.add(fakeBuild(drawn, 1000, 0), 9);
    ASSERT_EQ(store.bytes(), 5000u);
    EXPECT_TRUE(tilesToEvict(store, 5000, 9).empty()) << "within the budget";
    EXPECT_EQ(tilesToEvict(store, 4999, 9), std::vector<TileKey>({fine_old}));
    EXPECT_EQ(tilesToEvict(store, 2500, 9), std::vector<TileKey>({fine_old, coarse_old, middle}));
    // The tiles the last cull used stay even when the budget cannot hold them.
    EXPECT_EQ(tilesToEvict(store, 0, 9), std::vector<TileKey>({fine_old, coarse_old, middle, recent}));
    EXPECT_EQ(tilesToEvict(store, 0, 3), std::vector<TileKey>({fine_old, coarse_old, middle}));
}

}  // namespace
}  // namespace terrasynth::plugin
