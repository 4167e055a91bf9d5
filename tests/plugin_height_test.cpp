// TerrainNode::heightAt / heightRange (surface heights from resident tiles), prefetch and
// refinementDistance, headless (UPDATE + CULL, no GL) over a real DEM.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include <osg/Geometry>
#include <osg/MatrixTransform>

#include "headless_view.h"
#include "terrasynth_plugin/terrain_node.h"
#include "plugin_test_options.h"
#include "test_support.h"
#include "wait_until.h"

namespace terrasynth::plugin {
namespace {


struct Fixture {
    Heightfield dem = test::loadExemplarField("orom_alaska");
    HeightSource source = mirroredExemplarSource(dem);
    double spacing = dem.meters_per_pixel_x;
    osg::ref_ptr<TerrainNode> node = new TerrainNode(source, spacing, smallTiles());

    float sample(int64_t px, int64_t py, int level = 0) const {
        auto h = source({px, py, 1, 1}, level);
        EXPECT_TRUE(h) << h.message();
        return h ? h->at(0, 0) : 0.0f;
    }
    // The height of level-0 pixel position (px, py) (fractional) on the grid's triangles, written
    // independently of the node: barycentric weights in the cell's triangle.
    double onTriangles(double px, double py) const {
        const int64_t x0 = static_cast<int64_t>(std::floor(px)), y0 = static_cast<int64_t>(std::floor(py));
        const double fu = px - x0, fw = py - y0;
        const double nw = sample(x0, y0), ne = sample(x0 + 1, y0), sw = sample(x0, y0 + 1), se = sample(x0 + 1, y0 + 1);
        // Triangles (nw, sw, ne) and (ne, sw, se): the diagonal runs from north-east to south-west.
        if (fu + fw <= 1.0) return (1.0 - fu - fw) * nw + fu * ne + fw * sw;
        return (fu + fw - 1.0) * se + (1.0 - fw) * ne + (1.0 - fu) * sw;
    }
    std::optional<float> heightAtPixel(double px, double py) const { return node->heightAt(px * spacing, -py * spacing); }
};

TEST(PluginHeight, NothingResidentGivesNoHeight) {
    Fixture fx;
    EXPECT_FALSE(fx.node->heightAt(1000.0, -1000.0).has_value());
    EXPECT_FALSE(fx.node->heightRange({0, 0, 64, 64}).has_value());
}

TEST(PluginHeight, LevelZeroTilesGiveTheSamplesAndTheMeshTriangles) {
    Fixture fx;
    ASSERT_TRUE(fx.node->preload({0, 0, 128, 128}, 0));
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> pixel(0, 127);
    std::uniform_real_distribution<double> frac(0.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        const int px = pixel(rng), py = pixel(rng);
        const auto at_sample = fx.heightAtPixel(px, py);
        ASSERT_TRUE(at_sample.has_value());
        EXPECT_EQ(*at_sample, fx.sample(px, py)) << "sample " << px << "," << py;
        const double fx_ = px + frac(rng), fy = py + frac(rng);
        const auto inside = fx.heightAtPixel(fx_, fy);
        ASSERT_TRUE(inside.has_value());
        EXPECT_NEAR(*inside, fx.onTriangles(fx_, fy), 0.01) << "at " << fx_ << "," << fy;
    }
    // Either side of a cell's diagonal the two triangles give different heights (the split matters).
    const double below = *fx.heightAtPixel(10.3, 20.6), above = *fx.heightAtPixel(10.6, 20.3);
    EXPECT_NEAR(below, fx.onTriangles(10.3, 20.6), 0.01);
    EXPECT_NEAR(above, fx.onTriangles(10.6, 20.3), 0.01);
    // Outside the preloaded region nothing is resident.
    EXPECT_FALSE(fx.heightAtPixel(-300.5, 10.5).has_value());
    const auto range = fx.node->heightRange({0, 0, 128, 128});
    ASSERT_TRUE(range.has_value());
    EXPECT_LT(range->first, range->second);
}

TEST(PluginHeight, TheFinestResidentTileAnswers) {
    Fixture fx;
    ASSERT_TRUE(fx.node->preload({0, 0, 256, 256}, 2));
    // On level-2 tiles the samples are level-2 samples (means of 4x4 level-0 blocks).
    const auto coarse = fx.heightAtPixel(8.0, 12.0);
    ASSERT_TRUE(coarse.has_value());
    EXPECT_EQ(*coarse, fx.sample(2, 3, 2));
    ASSERT_TRUE(fx.node->preload({0, 0, 64, 64}, 0));
    const auto fine = fx.heightAtPixel(8.0, 12.0);
    ASSERT_TRUE(fine.has_value());
    EXPECT_EQ(*fine, fx.sample(8, 12));
    EXPECT_NE(*fine, *coarse);
    // Where no level-0 tile is resident the level-2 tile still answers.
    EXPECT_TRUE(fx.heightAtPixel(200.5, 200.5).has_value());
}

// Tiles reordered for the vertex cache keep no grid order in their geometry; heightAt reads the
// tiles' samples, so it answers there too, bit for bit as on tiles in grid order.
TEST(PluginHeight, VertexCacheOrderLeavesTheSurfaceAlone) {
    Fixture fx;
    TerrainNodeOptions o = smallTiles();
    o.optimize_order = true;
    osg::ref_ptr<TerrainNode> optimized = new TerrainNode(fx.source, fx.spacing, o);
    for (int level : {2, 0}) {
        ASSERT_TRUE(fx.node->preload({0, 0, 128, 128}, level));
        ASSERT_TRUE(optimized->preload({0, 0, 128, 128}, level));
    }
    // The same vertices in another order: vertex i is not grid vertex i.
    auto vertices = [](const osg::ref_ptr<osg::Node>& tile) {
        auto* transform = dynamic_cast<osg::MatrixTransform*>(tile.get());
        EXPECT_NE(transform, nullptr);
        const auto* v = static_cast<const osg::Vec3Array*>(transform->getChild(0)->asGeometry()->getVertexArray());
        return std::vector<osg::Vec3f>(v->begin(), v->end());
    };
    std::vector<osg::Vec3f> grid = vertices(fx.node->tileNode({0, 1, 0})), reordered = vertices(optimized->tileNode({0, 1, 0}));
    ASSERT_EQ(grid.size(), reordered.size());
    EXPECT_NE(grid, reordered);
    auto byPosition = [](const osg::Vec3f& a, const osg::Vec3f& b) { return a < b; };
    std::sort(grid.begin(), grid.end(), byPosition);
    std::sort(reordered.begin(), reordered.end(), byPosition);
    EXPECT_EQ(grid, reordered);

    std::mt19937 rng(11);
    std::uniform_real_distribution<double> coordinate(-10.0, 300.0);
    for (int i = 0; i < 300; ++i) {
        const double px = i < 100 ? std::floor(coordinate(rng)) : coordinate(rng), py = coordinate(rng);
        int level = -1, optimized_level = -1;
        const auto h = fx.node->heightAt(px * fx.spacing, -py * fx.spacing, &level);
        const auto ho = optimized->heightAt(px * fx.spacing, -py * fx.spacing, &optimized_level);
        ASSERT_EQ(h.has_value(), ho.has_value()) << "at " << px << "," << py;
        if (!h) continue;
        EXPECT_EQ(*ho, *h) << "at " << px << "," << py;
        EXPECT_EQ(optimized_level, level);
    }
    const auto at_sample = optimized->heightAt(37 * fx.spacing, -90 * fx.spacing);
    ASSERT_TRUE(at_sample.has_value());
    EXPECT_EQ(*at_sample, fx.sample(37, 90));
    EXPECT_NEAR(*optimized->heightAt(10.3 * fx.spacing, -20.6 * fx.spacing), fx.onTriangles(10.3, 20.6), 0.01);
}

TEST(PluginHeight, ExactFarFromTheOrigin) {
    Fixture fx;
    const int64_t far = 1000000;  // 10^6 pixels: 92,600 km east and south of the origin
    ASSERT_TRUE(fx.node->preload({far, far, 64, 64}, 0));
    for (int64_t d : {0, 1, 17, 63}) {
        const auto h = fx.heightAtPixel(static_cast<double>(far + d), static_cast<double>(far + 63 - d));
        ASSERT_TRUE(h.has_value());
        EXPECT_EQ(*h, fx.sample(far + d, far + 63 - d));
    }
    EXPECT_NEAR(*fx.heightAtPixel(far + 5.25, far + 9.5), fx.onTriangles(far + 5.25, far + 9.5), 0.01);
}

TEST(PluginHeight, ConcurrentQueriesWhileTilesPageInAndOut) {
    Fixture fx;
    test::HeadlessView view(fx.node.get());
    std::atomic<bool> stop{false};
    std::atomic<int> answered{0}, out_of_range{0};
    auto query = [&](unsigned seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> x(0.0, 60000.0);
        while (!stop) {
            const double wx = x(rng), wy = -x(rng);
            if (auto h = fx.node->heightAt(wx, wy)) {
                ++answered;
                if (*h < 0.0f || *h > 7000.0f) ++out_of_range;
            }
        }
    };
    std::thread a(query, 1u), b(query, 2u);
    // A flight across the region: tiles are merged, refined and evicted meanwhile.
    for (int f = 0; f < 300; ++f) {
        const double t = f / 300.0;
        const osg::Vec3d eye(5000 + 50000 * t, -5000 - 50000 * t, 4000);
        view.frame(eye, eye + osg::Vec3d(3000, -3000, -1500));
        std::this_thread::sleep_for(std::chrono::milliseconds(2));  // lets the workers build (no wait)
    }
    // However slowly the workers and the queries ran, the view at the end converges and is asked
    // enough times (a deadline, not a window).
    const osg::Vec3d end(55000, -55000, 4000);
    EXPECT_TRUE(test::waitUntil([&] {
        view.frame(end, end + osg::Vec3d(3000, -3000, -1500));
        return fx.node->settled() && answered > 100;
    }));
    stop = true;
    a.join();
    b.join();
    EXPECT_GT(answered.load(), 100);
    EXPECT_EQ(out_of_range.load(), 0);
}

TEST(PluginPrefetch, BuildsTilesAheadOfTheCamera) {
    Fixture fx;
    test::HeadlessView view(fx.node.get());
    const osg::Vec3d eye(5000, -5000, 4000), center(8000, -8000, 2000);
    // 90 km behind the camera (out of the frustum: the cull wants nothing there).
    const PixelWindow ahead{-700, -700, 64, 64};
    const std::vector<TileKey> keys = {{1, -6, -6}, {2, -3, -3}};  // level-1 and level-2 tiles over it
    for (int f = 0; f < 5; ++f) view.frame(eye, center);
    for (const TileKey& k : keys) ASSERT_FALSE(fx.node->tileNode(k)) << "already resident without prefetching";
    const bool all = test::waitUntil([&] {
        for (int level : {2, 1}) fx.node->prefetch(ahead, level);
        view.frame(eye, center);
        bool resident = true;
        for (const TileKey& k : keys) resident = resident && fx.node->tileNode(k);
        // The region spans more tiles than the two named; wait for every one asked for.
        return resident && fx.node->stats().prefetch_requests == 0;
    });
    EXPECT_TRUE(all) << "prefetched tiles never became resident";
    // Now the surface there is known without the camera having been near it.
    EXPECT_TRUE(fx.heightAtPixel(-680.5, -670.5).has_value());
    EXPECT_EQ(fx.node->stats().prefetch_requests, 0u);
}

TEST(PluginPrefetch, RefinementDistanceIsWhereTheCullDrawsEachLevel) {
    Fixture fx;
    EXPECT_EQ(fx.node->refinementDistance(0), 0.0);
    test::HeadlessView view(fx.node.get());
    const osg::Vec3d eye(20000, -20000, 4500), center(26000, -26000, 1500);
    int frames = 0;
    ASSERT_TRUE(test::waitUntil([&] {
        view.frame(eye, center);
        return ++frames > 3 && fx.node->settled();
    }));
    const double d0 = fx.node->refinementDistance(0);
    EXPECT_GT(d0, 0.0);
    EXPECT_DOUBLE_EQ(fx.node->refinementDistance(1), 2.0 * d0);
    EXPECT_DOUBLE_EQ(fx.node->refinementDistance(4), fx.node->options().view_radius_m);
    const TileLayout& layout = fx.node->layout();
    int checked = 0;
    for (const TileKey& k : fx.node->drawnTiles()) {
        if (k.level >= fx.node->options().max_level) continue;
        // A level-k tile is drawn because its parent was refined: the parent was nearer than the
        // level's distance. The cull measures to the 3D box; the horizontal distance is never more.
        const TileKey p = k.parent();
        const double m = layout.tileMeters(p.level), x0 = layout.westX(p), y1 = layout.northY(p);
        const double dx = std::max({x0 - eye.x(), 0.0, eye.x() - (x0 + m)});
        const double dy = std::max({(y1 - m) - eye.y(), 0.0, eye.y() - y1});
        EXPECT_LE(std::hypot(dx, dy), fx.node->refinementDistance(k.level) * (1.0 + 1e-9))
            << "tile " << k.level << "/" << k.x << "/" << k.y;
        ++checked;
    }
    EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace terrasynth::plugin
