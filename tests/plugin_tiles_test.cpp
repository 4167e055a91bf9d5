// Tile data model on a real DEM: windows are bit-identical to larger windows, neighbouring tiles
// share their edge vertices exactly, skirts hang below the edges.
#include <gtest/gtest.h>

#include <osg/Geometry>
#include <osg/MatrixTransform>

#include <cmath>
#include <cstring>
#include <map>

#include "terrasynth_plugin/height_source.h"
#include "terrasynth_plugin/tile_builder.h"
#include "test_support.h"

namespace terrasynth::plugin {
namespace {

Heightfield subWindow(const Heightfield& f, int x0, int y0, int w, int h) { return test::crop(f, x0, y0, w, h); }

bool sameBits(const Heightfield& a, const Heightfield& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.heights.data(), b.heights.data(), a.heights.size() * sizeof(float)) == 0;
}

// World-space vertices of a tile node (MatrixTransform over one Geometry).
std::vector<osg::Vec3d> worldVertices(osg::Node* node) {
    auto* mt = dynamic_cast<osg::MatrixTransform*>(node);
    EXPECT_NE(mt, nullptr);
    auto* geom = mt->getChild(0)->asGeometry();
    const auto* v = static_cast<const osg::Vec3Array*>(geom->getVertexArray());
    std::vector<osg::Vec3d> out;
    for (const auto& p : *v) out.push_back(osg::Vec3d(p) * mt->getMatrix());
    return out;
}

TEST(PluginTiles, ExemplarSourceWindowsAreBitIdenticalAcrossLevelsAndPeriods) {
    const Heightfield dem = test::loadExemplarField("orom_alaska");
    HeightSource source = mirroredExemplarSource(dem);
    for (int level : {0, 2, 4}) {
        // A window straddling negative coordinates and the mirror period.
        const PixelWindow big{-700, 1200, 300, 200};
        auto whole = source(big, level);
        ASSERT_TRUE(whole) << whole.message();
        auto part = source({big.x + 37, big.y + 53, 91, 64}, level);
        ASSERT_TRUE(part) << part.message();
        EXPECT_TRUE(sameBits(*part, subWindow(*whole, 37, 53, 91, 64))) << "level " << level;
        EXPECT_DOUBLE_EQ(whole->meters_per_pixel_x, dem.meters_per_pixel_x * (1 << level));
    }
    // Level 0 inside the first period is the DEM itself.
    auto inside = source({10, 20, 50, 40}, 0);
    ASSERT_TRUE(inside);
    EXPECT_TRUE(sameBits(*inside, subWindow(dem, 10, 20, 50, 40)));
    // Level 3 is the mean of the level-0 block (the DEM has relief, so this is not trivially true).
    auto coarse = source({5, 7, 1, 1}, 3);
    ASSERT_TRUE(coarse);
    double sum = 0.0;
    for (int y = 56; y < 64; ++y)
        for (int x = 40; x < 48; ++x) sum += dem.at(x, y);
    EXPECT_NEAR(coarse->at(0, 0), sum / 64.0, 1e-3);
    EXPECT_FALSE(source({0, 0, 4, 4}, 30)) << "a level beyond the mirror period must be refused";
}

TEST(PluginTiles, TileHeightsAreAWindowOfTheWholeGrid) {
    const Heightfield dem = test::loadExemplarField("orom_rockies");
    HeightSource source = mirroredExemplarSource(dem);
    TileBuildSettings s;
    s.layout = {64, dem.meters_per_pixel_x};
    const TileKey key{1, -3, 2};
    const TileBuild tile = buildTile(source, key, s);
    ASSERT_TRUE(tile.status) << tile.status.message();
    const PixelWindow w = tileReadWindow(key, s);
    auto larger = source({w.x - 10, w.y - 5, w.width + 30, w.height + 20}, key.level);
    ASSERT_TRUE(larger);
    EXPECT_EQ(tile.heights_hash, hashHeights(subWindow(*larger, 10, 5, w.width, w.height)));
    EXPECT_LT(tile.min_height, tile.max_height);
    EXPECT_GT(tile.bytes, size_t{65 * 65 * 24});
}

TEST(PluginTiles, NeighbouringTilesShareEdgeVerticesAndHangSkirts) {
    const Heightfield dem = test::loadExemplarField("orom_himalaya-everest");
    HeightSource source = mirroredExemplarSource(dem);
    for (int step : {1, 2}) {
        TileBuildSettings s;
        s.layout = {32, dem.meters_per_pixel_x};
        s.mesh_step = step;
        const TileKey west{2, 4, 1}, east{2, 5, 1};
        const TileBuild a = buildTile(source, west, s), b = buildTile(source, east, s);
        ASSERT_TRUE(a.status && b.status);
        const double edge_x = s.layout.westX(east);
        // Top-surface vertices on the shared edge, by northing: each must have the same height.
        auto edgeOf = [&](const TileBuild& t) {
            std::map<long long, double> heights;
            for (const auto& v : worldVertices(t.node.get()))
                if (std::abs(v.x() - edge_x) < 1e-3 && v.z() >= t.min_height - 1e-3) {
                    const long long y = std::llround(v.y() * 1000.0);
                    auto it = heights.find(y);
                    if (it == heights.end() || v.z() > it->second) heights[y] = v.z();  // skip skirt
                }
            return heights;
        };
        const auto ea = edgeOf(a), eb = edgeOf(b);
        ASSERT_EQ(ea.size(), size_t(32 / step + 1));
        ASSERT_EQ(ea.size(), eb.size());
        for (const auto& [y, z] : ea) {
            ASSERT_TRUE(eb.count(y));
            EXPECT_FLOAT_EQ(static_cast<float>(z), static_cast<float>(eb.at(y)));
        }
        // The skirt hangs the tile's relief plus two spacings below its edge, so it reaches below
        // every sample of the tile; the bound covers it.
        double lowest = 1e30;
        for (const auto& v : worldVertices(a.node.get())) lowest = std::min(lowest, v.z());
        const double depth = (a.max_height - a.min_height) + 2.0 * s.layout.spacing(2);
        EXPECT_LE(lowest, a.min_height - 2.0 * s.layout.spacing(2) + 1e-2);
        EXPECT_GE(lowest, a.box.zMin() - 1e-2);
        EXPECT_NEAR(a.box.zMin(), a.min_height - depth, 0.01);
    }
}

TEST(PluginTiles, GeomorphTargetsLieOnTheParentMesh) {
    const Heightfield dem = test::loadExemplarField("orom_alaska");
    HeightSource source = mirroredExemplarSource(dem);
    TileBuildSettings s;
    s.layout = {32, dem.meters_per_pixel_x};
    s.geomorph = true;
    s.max_level = 4;
    const TileKey parent_key{2, 3, 5};
    const TileBuild parent = buildTile(source, parent_key, s);
    ASSERT_TRUE(parent.status);
    // Parent top-surface heights by world position.
    std::map<std::pair<long long, long long>, double> parent_z;
    for (const auto& v : worldVertices(parent.node.get()))
        if (v.z() >= parent.min_height - 1e-3) parent_z[{std::llround(v.x() * 100), std::llround(v.y() * 100)}] = v.z();
    size_t on_parent_vertices = 0;
    for (int c = 0; c < 4; ++c) {
        const TileBuild child = buildTile(source, parent_key.child(c % 2, c / 2), s);
        ASSERT_TRUE(child.status);
        auto* mt = dynamic_cast<osg::MatrixTransform*>(child.node.get());
        auto* geom = mt->getChild(0)->asGeometry();
        const auto* coarse = dynamic_cast<const osg::FloatArray*>(geom->getVertexAttribArray(kCoarseHeightAttribute));
        ASSERT_NE(coarse, nullptr);
        const auto world = worldVertices(child.node.get());
        ASSERT_EQ(coarse->size(), world.size());
        for (size_t i = 0; i < world.size(); ++i) {
            auto it = parent_z.find({std::llround(world[i].x() * 100), std::llround(world[i].y() * 100)});
            if (it == parent_z.end() || world[i].z() < child.min_height - 1e-3) continue;
            // Where a parent vertex is, the morph target is exactly the parent's height.
            EXPECT_FLOAT_EQ((*coarse)[i], static_cast<float>(it->second));
            ++on_parent_vertices;
        }
    }
    EXPECT_EQ(on_parent_vertices, size_t(4 * 17 * 17));  // every other vertex of each child

    // The manager takes the parent samples from the resident parent's vertices instead of a second
    // synthesis call: they must be the source's samples bit for bit, and give the same tile.
    for (int step : {1, 2}) {
        s.mesh_step = step;
        const TileBuild p = buildTile(source, parent_key, s);
        const TileKey child = parent_key.child(1, 0);
        const Heightfield from_node = parentSamplesFromNode(*p.node, child, s);
        ASSERT_EQ(from_node.width, 17);
        auto from_source = source({child.x * 16, child.y * 16, 17, 17}, child.level + 1);
        ASSERT_TRUE(from_source);
        for (int y = 0; y < 17; y += step)
            for (int x = 0; x < 17; x += step) ASSERT_EQ(from_node.at(x, y), from_source->at(x, y));
        const TileBuild a = buildTile(source, child, s), b = buildTile(source, child, s, &from_node);
        ASSERT_TRUE(a.status && b.status);
        auto coarseOf = [](const TileBuild& t) {
            auto* g = dynamic_cast<osg::MatrixTransform*>(t.node.get())->getChild(0)->asGeometry();
            const auto* c = static_cast<const osg::FloatArray*>(g->getVertexAttribArray(kCoarseHeightAttribute));
            return std::vector<float>(c->begin(), c->end());
        };
        EXPECT_EQ(coarseOf(a), coarseOf(b));
    }
    // Roots (level == max_level) have nothing to morph to.
    const TileBuild root = buildTile(source, {4, 0, 0}, s);
    ASSERT_TRUE(root.status);
    auto* geom = dynamic_cast<osg::MatrixTransform*>(root.node.get())->getChild(0)->asGeometry();
    EXPECT_EQ(geom->getVertexAttribArray(kCoarseHeightAttribute), nullptr);
}

TEST(PluginTiles, SourceErrorsNameTheTile) {
    HeightSource failing = [](const PixelWindow&, int) -> Result<Heightfield> {
        return Status::error("no exemplar");
    };
    TileBuildSettings s;
    s.layout = {16, 10.0};
    const TileBuild t = buildTile(failing, {3, 1, -2}, s);
    EXPECT_FALSE(t.status);
    EXPECT_NE(t.status.message().find("tile 3/1/-2"), std::string::npos) << t.status.message();
    HeightSource wrong_size = [](const PixelWindow&, int) -> Result<Heightfield> { return Heightfield(3, 3, 1.0); };
    EXPECT_FALSE(buildTile(wrong_size, {0, 0, 0}, s).status);
}

}  // namespace
}  // namespace terrasynth::plugin
