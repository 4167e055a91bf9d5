// Issue 20 for exports: tiles one cell wide (the last tile of a region that the tile size does not
// divide) mesh without a precondition abort and still cover their area exactly; absurd tile counts
// are refused before anything is allocated.
#include <gtest/gtest.h>

#include "terrasynth/gltf_export.h"
#include "terrasynth/mesh.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

double planArea(const TileMesh& m) {
    double area = 0.0;
    for (size_t t = 0; t < m.skirt_first_index / 3; ++t) {  // surface triangles (skirts follow)
        const float* a = &m.positions[3 * m.indices[3 * t]];
        const float* b = &m.positions[3 * m.indices[3 * t + 1]];
        const float* c = &m.positions[3 * m.indices[3 * t + 2]];
        const double z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        EXPECT_GT(z, 0.0) << "triangle " << t << " is degenerate or clockwise";
        area += 0.5 * z;
    }
    return area;
}

TEST(ExportHardening, NarrowStitchedTilesCoverTheirArea) {
    const Heightfield field = test::loadExemplarField("orom_alaska");
    // Apron of 1 on every side: w x h samples mesh (w-3) x (h-3) quads.
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{4, 40}, {5, 40}, {40, 4}, {6, 6}, {4, 4}}) {
        for (int step : {2, 4}) {
            MeshOptions options;
            options.border = 1;
            options.step = step;
            options.full_res_border = true;
            const TileMesh m = meshHeightfield(test::crop(field, 30, 40, w, h), options);
            const double expected = (w - 3) * field.meters_per_pixel_x * (h - 3) * field.meters_per_pixel_y;
            EXPECT_NEAR(planArea(m), expected, 1e-5 * expected) << w << "x" << h << " step " << step;
        }
    }
}

TEST(ExportHardening, TileSizesThatLeaveASliverExport) {
    // Issue 20: a 256^2 heightmap with --tile 254 --lods 2 hit a precondition in grid_mesh.cpp.
    const Heightfield field = test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 256, 256);
    const std::string dir = test::scratchDir("export_hardening_sliver");
    for (int tile : {254, 253, 255, 127}) {
        GltfExportOptions options;
        options.region = {0, 0, 256, 256};
        options.tile_size = tile;
        options.lods = 3;
        auto stats = exportGltf(dir + "/t.glb", heightSourceFromField(field), options);
        ASSERT_TRUE(stats) << "tile " << tile << ": " << stats.message();
        EXPECT_EQ(stats->tiles_x, 255 / tile + (255 % tile ? 1 : 0));
    }
}

TEST(ExportHardening, AbsurdTileCountsAreRefused) {
    GltfExportOptions options;
    options.region = {0, 0, 4096, 4096};
    options.tile_size = 1;
    auto stats = exportGltf(test::scratchDir("export_hardening_tiles") + "/t.glb",
                            heightSourceFromField(Heightfield(4096, 4096, 10.0)), options);
    ASSERT_FALSE(stats);
    EXPECT_NE(stats.message().find("tile_size: 1 cuts the region into"), std::string::npos) << stats.message();
}

}  // namespace
