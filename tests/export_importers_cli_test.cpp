// glTF that opens right in the tools users import it with: Debian's Blender (headless, its own glTF
// importer) and three.js's GLTFLoader (under node). Each sees one terrain, with the heightmap's extent
// and height range; the MSFT_lod layout keeps its lower LODs reachable but undrawn in three.js.
// Skipped, with the reason, only where blender or node is not installed (scripts/setup.sh installs
// them; three comes with `npm ci --prefix scripts`).
#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include <nlohmann/json.hpp>

#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

std::string repoDir() { return test::dataDir() + "/.."; }

// A 257x193-sample region of the Alaska exemplar, tiles of 64 quads: 4 x 3 tiles.
constexpr int kX = 40, kY = 30, kW = 257, kH = 193, kTiles = 12;

struct Exported {
    std::string dir;
    std::vector<size_t> lod_vertices;  // as the exporter reports them
};

Exported exportRegion(const std::string& name, const std::string& layout) {
    Exported e;
    e.dir = test::scratchDir(name);
    const test::CliRun run = test::runTerrasynth("export --heightmap '" + test::dataDir() + "/exemplars/orom_alaska.png' -o '" +
                                                 e.dir + "/terrain.glb' --region " + std::to_string(kX) + "," + std::to_string(kY) +
                                                 "," + std::to_string(kW) + "," + std::to_string(kH) +
                                                 " --tile 64 --lods 3 --lod-layout " + layout);
    EXPECT_EQ(run.exit_code, 0) << run.out;
    const std::regex lod_line(R"(LOD \d+: (\d+) vertices)");
    for (std::sregex_iterator it(run.out.begin(), run.out.end(), lod_line), end; it != end; ++it)
        e.lod_vertices.push_back(std::stoul((*it)[1]));
    EXPECT_EQ(e.lod_vertices.size(), 3u) << run.out;
    return e;
}

// The region's own heights: what the meshes' height range must be.
HeightRange regionRange(double* spacing) {
    auto ex = readExemplar(test::dataDir() + "/exemplars/orom_alaska.png");
    EXPECT_TRUE(ex) << ex.message();
    *spacing = ex->field.meters_per_pixel_x;
    HeightRange r{INFINITY, -INFINITY};
    for (int y = kY; y < kY + kH; ++y)
        for (int x = kX; x < kX + kW; ++x) r.min = std::min(r.min, ex->field.at(x, y)), r.max = std::max(r.max, ex->field.at(x, y));
    return r;
}

// The JSON line a stats script printed after `marker` (empty object when missing).
nlohmann::json statsLine(const std::string& out, const std::string& marker) {
    const size_t at = out.find(marker);
    if (at == std::string::npos) return nlohmann::json::object();
    const size_t begin = at + marker.size(), end = out.find('\n', begin);
    return nlohmann::json::parse(out.substr(begin, end - begin), nullptr, false);
}

}  // namespace

TEST(Importers, BlenderImportsTheDefaultExportAsOneTerrain) {
    if (!test::haveProgram("blender")) GTEST_SKIP() << "blender is not installed (Debian blender, scripts/setup.sh)";
    const Exported e = exportRegion("importers_blender", "files");
    double spacing = 0;
    const HeightRange range = regionRange(&spacing);
    for (int lod : {0, 2}) {
        const std::string file = e.dir + (lod == 0 ? "/terrain.glb" : "/terrain_lod2.glb");
        const test::CliRun run = test::runCommand("blender -b --factory-startup --python-exit-code 1 --python '" + repoDir() +
                                                  "/scripts/blender_gltf_stats.py' -- '" + file + "'");
        ASSERT_EQ(run.exit_code, 0) << run.out;
        const nlohmann::json stats = statsLine(run.out, "BLENDER_STATS ");
        ASSERT_TRUE(stats.contains("meshes")) << run.out;
        std::printf("Blender 3.4, %s: %d visible meshes, %zu vertices\n", file.c_str(), stats["meshes"].get<int>(),
                    stats["vertices"].get<size_t>());
        EXPECT_EQ(stats["meshes"].get<int>(), kTiles) << "one mesh per tile, no copy per LOD";
        EXPECT_EQ(stats["vertices"].get<size_t>(), e.lod_vertices[lod]);
        // Blender's frame: X east, Y north (glTF's Z south negated), Z up.
        EXPECT_NEAR(stats["min"][0].get<double>(), 0.0, 1e-3);
        EXPECT_NEAR(stats["max"][0].get<double>(), (kW - 1) * spacing, 1e-2);
        EXPECT_NEAR(stats["min"][1].get<double>(), -(kH - 1) * spacing, 1e-2);
        EXPECT_NEAR(stats["max"][1].get<double>(), 0.0, 1e-3);
        // LOD 2 keeps every border sample but skips interior ones, so only LOD 0 must reach both ends.
        if (lod == 0) {
            EXPECT_NEAR(stats["min"][2].get<double>(), range.min, 1e-2);
            EXPECT_NEAR(stats["max"][2].get<double>(), range.max, 1e-2);
        } else {
            EXPECT_GE(stats["min"][2].get<double>(), range.min - 1e-2);
            EXPECT_LE(stats["max"][2].get<double>(), range.max + 1e-2);
        }
    }
}

TEST(Importers, ThreeJsDrawsOneTerrainInBothLayoutsAndReachesTheMsftLods) {
    if (!test::haveProgram("node")) GTEST_SKIP() << "node is not installed (scripts/setup.sh)";
    ASSERT_TRUE(!test::readFile(repoDir() + "/scripts/node_modules/three/package.json").empty())
        << "three is not installed: run `npm ci --prefix scripts` in the repository";
    double spacing = 0;
    const HeightRange range = regionRange(&spacing);
    for (const char* layout : {"files", "msft"}) {
        const Exported e = exportRegion(std::string("importers_three_") + layout, layout);
        const test::CliRun run = test::runCommand("node '" + repoDir() + "/scripts/three_gltf_stats.mjs' '" + e.dir + "/terrain.glb'");
        ASSERT_EQ(run.exit_code, 0) << run.out;
        const nlohmann::json stats = nlohmann::json::parse(run.out, nullptr, false);
        ASSERT_TRUE(stats.is_object() && stats.contains("meshes")) << run.out;
        std::printf("three.js, %s layout: %d meshes drawn, %zu vertices, %d nodes, %d MSFT_lod nodes reachable\n", layout,
                    stats["meshes"].get<int>(), stats["vertices"].get<size_t>(), stats["nodes"].get<int>(),
                    stats["lodNodes"].get<int>());
        EXPECT_EQ(stats["meshes"].get<int>(), kTiles) << layout;
        EXPECT_EQ(stats["vertices"].get<size_t>(), e.lod_vertices[0]) << layout;
        EXPECT_NEAR(stats["max"][0].get<double>(), (kW - 1) * spacing, 1e-2);
        EXPECT_NEAR(stats["max"][2].get<double>(), (kH - 1) * spacing, 1e-2);  // glTF Z south
        EXPECT_NEAR(stats["min"][1].get<double>(), range.min, 1e-2);
        EXPECT_NEAR(stats["max"][1].get<double>(), range.max, 1e-2);
        const bool msft = std::string(layout) == "msft";
        EXPECT_EQ(stats["nodes"].get<int>(), 1 + kTiles * (msft ? 3 : 1)) << layout;
        EXPECT_EQ(stats["lodNodes"].get<int>(), msft ? 2 * kTiles : 0) << layout;
    }
}
