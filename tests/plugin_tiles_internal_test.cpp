// Tiles on a real DEM: windows are bit-identical to larger windows, a tile's data is the window it
// read, neighbouring tiles share their edge vertices exactly, skirts hang below the edges, geomorph
// targets lie on the parent's mesh and come from the parent's data.
#include <gtest/gtest.h>

#include <osg/Geometry>
#include <osg/MatrixTransform>

#include <cmath>
#include <cstring>
#include <map>

#include "terrasynth_plugin/height_source.h"
#include "test_support.h"
#include "tile_builder.h"

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
    const TileData& data = *tile.data;
    EXPECT_EQ(data.hash, hashHeights(subWindow(*larger, 10, 5, w.width, w.height)));
    EXPECT_LT(data.min_height, data.max_height);
    EXPECT_GT(tile.bytes, size_t{65 * 65 * 24});
    // The data is the window as read (apron included), placed like the layout's tile.
    EXPECT_TRUE(data.key == key);
    EXPECT_TRUE(sameBits(data.heights, subWindow(*larger, 10, 5, w.width, w.height)));
    EXPECT_EQ(data.apron, 1);
    EXPECT_EQ(data.tileSize(), 64);
    EXPECT_EQ(data.sample(0, 0), larger->at(11, 6));
    EXPECT_DOUBLE_EQ(data.west_x, s.layout.westX(key));
    EXPECT_DOUBLE_EQ(data.north_y, s.layout.northY(key));
    EXPECT_DOUBLE_EQ(data.spacing_m, s.layout.spacing(key.level));
    EXPECT_TRUE(data.types.empty());
    EXPECT_EQ(data.bytes(), size_t(67 * 67) * sizeof(float));
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
                if (std::abs(v.x() - edge_x) < 1e-3 && v.z() >= t.data->min_height - 1e-3) {
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
        const TileData& da = *a.data;
        const double depth = (da.max_height - da.min_height) + 2.0 * s.layout.spacing(2);
        EXPECT_LE(lowest, da.min_height - 2.0 * s.layout.spacing(2) + 1e-2);
        EXPECT_GE(lowest, a.box.zMin() - 1e-2);
        EXPECT_NEAR(a.box.zMin(), da.min_height - depth, 0.01);
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
        if (v.z() >= parent.data->min_height - 1e-3) parent_z[{std::llround(v.x() * 100), std::llround(v.y() * 100)}] = v.z();
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
            if (it == parent_z.end() || world[i].z() < child.data->min_height - 1e-3) continue;
            // Where a parent vertex is, the morph target is exactly the parent's height.
            EXPECT_FLOAT_EQ((*coarse)[i], static_cast<float>(it->second));
            ++on_parent_vertices;
        }
    }
    EXPECT_EQ(on_parent_vertices, size_t(4 * 17 * 17));  // every other vertex of each child

    // The manager takes the parent samples from the resident parent's data instead of a second
    // synthesis call: they must be the source's samples bit for bit, and give the same tile. They
    // are also the parent's top-surface vertex heights (where its mesh has vertices): the render
    // model agrees with the data model, in vertex order or reordered for the vertex cache.
    for (int step : {1, 2}) {
        for (bool optimize : {false, true}) {
            s.mesh_step = step;
            s.optimize_order = optimize;
            const TileBuild p = buildTile(source, parent_key, s);
            ASSERT_TRUE(p.status);
            for (int c = 0; c < 4; ++c) {
                const TileKey child = parent_key.child(c % 2, c / 2);
                const Heightfield from_data = parentSamples(*p.data, child);
                ASSERT_EQ(from_data.width, 17);
                ASSERT_EQ(from_data.height, 17);
                auto from_source = source({child.x * 16, child.y * 16, 17, 17}, child.level + 1);
                ASSERT_TRUE(from_source);
                EXPECT_TRUE(sameBits(from_data, *from_source)) << "child " << c;
                const TileBuild a = buildTile(source, child, s), b = buildTile(source, child, s, p.data.get());
                ASSERT_TRUE(a.status && b.status);
                auto coarseOf = [](const TileBuild& t) {
                    auto* g = dynamic_cast<osg::MatrixTransform*>(t.node.get())->getChild(0)->asGeometry();
                    const auto* f = static_cast<const osg::FloatArray*>(g->getVertexAttribArray(kCoarseHeightAttribute));
                    return std::vector<float>(f->begin(), f->end());
                };
                EXPECT_EQ(coarseOf(a), coarseOf(b));
            }
            // Every top-surface vertex of the parent sits on a sample of its data, at that sample's height.
            const double spacing = s.layout.spacing(parent_key.level);
            size_t top = 0;
            for (const auto& v : worldVertices(p.node.get())) {
                const long long col = std::llround((v.x() - p.data->west_x) / spacing);
                const long long row = std::llround((p.data->north_y - v.y()) / spacing);
                ASSERT_TRUE(col >= 0 && row >= 0 && col <= 32 && row <= 32);
                EXPECT_NEAR(v.x(), p.data->west_x + col * spacing, 1e-3 * spacing);
                const float h = p.data->sample(static_cast<int>(col), static_cast<int>(row));
                if (static_cast<float>(v.z()) < h) continue;  // a skirt vertex hangs below its sample
                EXPECT_EQ(static_cast<float>(v.z()), h);
                ++top;
            }
            EXPECT_EQ(top, size_t(32 / step + 1) * size_t(32 / step + 1));
        }
    }
    // Roots (level == max_level) have nothing to morph to.
    const TileBuild root = buildTile(source, {4, 0, 0}, s);
    ASSERT_TRUE(root.status);
    auto* geom = dynamic_cast<osg::MatrixTransform*>(root.node.get())->getChild(0)->asGeometry();
    EXPECT_EQ(geom->getVertexAttribArray(kCoarseHeightAttribute), nullptr);
}

TEST(PluginTiles, DataKeepsTheTypesAndSameSamplesTellsRebuildsApart) {
    const Heightfield dem = test::loadExemplarField("orom_rockies");
    HeightSource source = mirroredExemplarSource(dem);
    TileBuildSettings s;
    s.layout = {32, dem.meters_per_pixel_x};
    const TileKey key{1, 2, 3};
    // Three types in diagonal stripes of the global grid.
    auto stripe = [](int64_t x, int64_t y) { return static_cast<uint8_t>((x + y) % 3); };
    TypeSource types = [stripe](const PixelWindow& w, int) -> Result<std::vector<uint8_t>> {
        std::vector<uint8_t> ids(static_cast<size_t>(w.width) * w.height);
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) ids[static_cast<size_t>(y) * w.width + x] = stripe(w.x + x, w.y + y);
        return ids;
    };
    const TileBuild plain = buildTile(source, key, s), typed = buildTile(source, key, s, nullptr, &types),
                    again = buildTile(source, key, s, nullptr, &types);
    ASSERT_TRUE(plain.status && typed.status && again.status);
    const TileData& data = *typed.data;
    ASSERT_EQ(data.types.size(), size_t(33 * 33));
    EXPECT_EQ(data.bytes(), size_t(35 * 35) * sizeof(float) + 33 * 33);
    auto* geometry = dynamic_cast<osg::MatrixTransform*>(typed.node.get())->getChild(0)->asGeometry();
    const auto* vertex_types = dynamic_cast<const osg::FloatArray*>(geometry->getVertexAttribArray(kTypeAttribute));
    ASSERT_NE(vertex_types, nullptr);
    for (int row = 0; row <= 32; row += 8)
        for (int col = 0; col <= 32; col += 4) {
            const uint8_t expected = stripe(key.x * 32 + col, key.y * 32 + row);
            EXPECT_EQ(data.types[static_cast<size_t>(row) * 33 + col], expected);
            EXPECT_EQ((*vertex_types)[static_cast<size_t>(row) * 33 + col], float(expected));  // grid order
        }
    EXPECT_TRUE(sameBits(plain.data->heights, data.heights));
    EXPECT_FALSE(sameSamples(*plain.data, data)) << "same heights, other types";
    EXPECT_TRUE(sameSamples(data, *again.data));
    // A change in one apron sample alone (north of the corner: it shapes the corner's normal) makes
    // another tile.
    HeightSource bumped = editedSource(source, [](const PixelWindow&, int, Heightfield& f) { f.at(1, 0) += 0.5f; });
    const TileBuild edited = buildTile(bumped, key, s);
    ASSERT_TRUE(edited.status);
    EXPECT_FALSE(sameSamples(*plain.data, *edited.data));
    EXPECT_EQ(plain.data->min_height, edited.data->min_height);
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
