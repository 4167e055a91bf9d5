// Engine presets (`terrasynth export --preset unreal|unity|godot`): the engines' sizes, byte order
// and row order, tiles above one landscape, splat masks, and heights that come back through the
// stated scale within one 16-bit step.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "terrasynth/engine_heightmap.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

// 16-bit samples of a preset's heightmap, little-endian for .r16/.raw.
std::vector<uint16_t> readSamples(const std::string& path, int width, int height) {
    if (path.size() > 4 && path.substr(path.size() - 4) == ".png") {
        auto png = readPng16(path);
        EXPECT_TRUE(png) << png.message();
        EXPECT_EQ(png->width, width);
        EXPECT_EQ(png->height, height);
        return png ? png->samples : std::vector<uint16_t>();
    }
    const std::string bytes = test::readFile(path);
    EXPECT_EQ(bytes.size(), size_t(width) * height * 2) << path;
    std::vector<uint16_t> samples(bytes.size() / 2);
    for (size_t i = 0; i < samples.size(); ++i)
        samples[i] = uint16_t(uint8_t(bytes[2 * i]) | (uint8_t(bytes[2 * i + 1]) << 8));
    return samples;
}

nlohmann::json readJson(const std::string& path) { return nlohmann::json::parse(test::readFile(path), nullptr, false); }

// Heights the engine would build from the file, through the numbers the preset printed, row 0 north.
std::vector<double> decodeAsEngine(const std::string& engine, const nlohmann::json& j, const std::vector<uint16_t>& v, int w, int h) {
    std::vector<double> out(v.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t o = size_t(y) * w + x;
            if (engine == "unreal") {  // height_cm = location_z + (value - 32768) * scale_z / 128
                const double z = j["unreal"]["location_z_cm"].get<double>() + (v[o] - 32768.0) * j["unreal"]["scale"][2].get<double>() / 128.0;
                out[o] = z / 100.0;
            } else if (engine == "unity") {  // row 0 is south; 0..65535 spans the terrain height above position y
                const size_t file = size_t(h - 1 - y) * w + x;
                out[o] = j["unity"]["position_y_m"].get<double>() + v[file] / 65535.0 * j["unity"]["terrain_size_m"][1].get<double>();
            } else {  // Terrain3D: r16_range
                const double lo = j["godot"]["r16_range"][0].get<double>(), hi = j["godot"]["r16_range"][1].get<double>();
                out[o] = lo + v[o] / 65535.0 * (hi - lo);
            }
        }
    return out;
}

}  // namespace

TEST(EnginePresets, PlansUseTheEnginesSizes) {
    auto plan = [](Engine e, int w, int h, bool endless) {
        auto p = planEngineHeightmap(e, {0, 0, w, h}, endless);
        EXPECT_TRUE(p) << p.message();
        return p ? *p : EnginePlan();
    };
    // Unreal: 126-quad components (63x63 sections, 2x2) up to 4033, 254-quad ones for 8129.
    EnginePlan p = plan(Engine::Unreal, 1024, 1024, true);
    EXPECT_EQ(p.region.width, 2017);
    EXPECT_EQ(p.component_quads, 126);
    EXPECT_EQ(plan(Engine::Unreal, 1024, 1024, false).region.width, 1009);
    p = plan(Engine::Unreal, 500, 240, true);
    EXPECT_EQ(p.region.width, 505);
    EXPECT_EQ(p.region.height, 253);
    p = plan(Engine::Unreal, 8000, 3000, true);
    EXPECT_EQ(p.component_quads, 254);
    EXPECT_EQ(p.region.width, 8129);
    EXPECT_EQ(p.region.height, 4065);
    // Above one landscape: 2017-sample tiles sharing their edges.
    p = plan(Engine::Unreal, 9000, 2100, true);
    EXPECT_EQ(p.tiles_x, 5);
    EXPECT_EQ(p.tiles_y, 2);
    EXPECT_EQ(p.region.width, 5 * 2016 + 1);
    EXPECT_EQ(p.tile(1, 1).x, 2016);
    // Unity: square 2^n + 1.
    EXPECT_EQ(plan(Engine::Unity, 1024, 700, true).region.width, 1025);
    EXPECT_EQ(plan(Engine::Unity, 1024, 700, true).region.height, 1025);
    EXPECT_EQ(plan(Engine::Unity, 1024, 700, false).region.width, 513);
    p = plan(Engine::Unity, 5000, 300, true);
    EXPECT_EQ(p.tiles_x, 2);
    EXPECT_EQ(p.tiles_y, 1);
    EXPECT_EQ(p.region.width, 8193);
    // Godot's Terrain3D takes any size.
    p = plan(Engine::Godot, 1000, 700, true);
    EXPECT_EQ(p.region.width, 1000);
    EXPECT_EQ(p.region.height, 700);
    // Too small to crop to any size is an error, not an empty file.
    EXPECT_FALSE(planEngineHeightmap(Engine::Unity, {0, 0, 20, 20}, false));
    EXPECT_FALSE(engineNamed("cryengine"));
}

TEST(EnginePresets, TilesShareEdgesAndAreNamedForTheEnginesTiledImport) {
    // An analytic source (any window, level 0): a tilted plane with ripples.
    const HeightSource source = [](const PixelWindow& w, int) -> Result<Heightfield> {
        Heightfield f(w.width, w.height, 2.0);
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) {
                const double gx = double(w.x + x), gy = double(w.y + y);
                f.at(x, y) = float(100.0 + 0.02 * gx - 0.01 * gy + 5.0 * std::sin(gx * 0.01) * std::cos(gy * 0.013));
            }
        return f;
    };
    const std::string dir = test::scratchDir("presets_tiles");
    for (const char* engine : {"unreal", "unity"}) {
        const bool unreal = std::string(engine) == "unreal";
        // Just over one landscape: 8129 (Unreal) and 4097 (Unity) samples.
        auto plan = planEngineHeightmap(*engineNamed(engine), {0, 0, unreal ? 8200 : 4200, 100}, true);
        ASSERT_TRUE(plan) << plan.message();
        EngineExportOptions options;
        options.path = dir + "/" + engine + (unreal ? ".r16" : ".raw");
        FileTransaction transaction;
        auto written = stageEngineHeightmap(transaction, *plan, source, options);
        ASSERT_TRUE(written) << written.message();
        ASSERT_TRUE(transaction.commit());
        const nlohmann::json j = readJson(written->json_path);
        ASSERT_EQ(j["heightmaps"].size(), size_t(plan->tiles_x * plan->tiles_y));
        EXPECT_EQ(j["heightmaps"][1]["file"].get<std::string>(), unreal ? "unreal_x1_y0.r16" : "unity_1_0.raw");
        // Neighbouring tiles repeat their shared edge column sample for sample.
        const int tw = plan->tile_width, th = plan->tile_height;
        const std::vector<uint16_t> a = readSamples(dir + "/" + j["heightmaps"][0]["file"].get<std::string>(), tw, th);
        const std::vector<uint16_t> b = readSamples(dir + "/" + j["heightmaps"][1]["file"].get<std::string>(), tw, th);
        for (int y = 0; y < th; y += 97) ASSERT_EQ(a[size_t(y) * tw + tw - 1], b[size_t(y) * tw]) << engine << " row " << y;
        std::printf("%s\n", written->summary.c_str());
    }
}

TEST(EnginePresets, ProjectHeightsRoundTripThroughTheStatedScaleWithinOneStep) {
    const std::string dir = test::scratchDir("presets_roundtrip");
    const std::string project = test::defaultDatabaseProject(dir, 5);
    // A 250x200 region at level 1; the presets grow it east and south to their sizes.
    const std::string region = " --region 40,60,250,200 --level 1";
    struct Case {
        const char* engine;
        const char* file;
        int width, height;
    };
    for (const Case& c : {Case{"unreal", "unreal.png", 253, 253}, Case{"unity", "unity.raw", 257, 257}, Case{"godot", "godot.r16", 250, 200}}) {
        const test::CliRun run = test::runTerrasynth("export '" + project + "' --preset " + c.engine + region + " -o '" + dir + "/" + c.file + "'");
        ASSERT_EQ(run.exit_code, 0) << run.out;
        std::printf("%s", run.out.c_str());
        const std::string stem = dir + "/" + std::string(c.file).substr(0, std::string(c.file).find('.'));
        const nlohmann::json j = readJson(stem + ".json");
        ASSERT_TRUE(j.is_object()) << stem << ".json";
        EXPECT_NE(run.out.find(j["import"].get<std::string>()), std::string::npos) << "the printed line is the JSON's";
        ASSERT_EQ(j["region"][2].get<int>(), c.width) << c.engine;
        ASSERT_EQ(j["region"][3].get<int>(), c.height) << c.engine;
        // The same samples as floats, through the same height source.
        const std::string ref = stem + "_reference.f32";
        const test::CliRun export_ref = test::runTerrasynth("export '" + project + "' --level 1 --region 40,60," + std::to_string(c.width) +
                                                            "," + std::to_string(c.height) + " -o '" + ref + "'");
        ASSERT_EQ(export_ref.exit_code, 0) << export_ref.out;
        auto reference = readExemplar(ref);
        ASSERT_TRUE(reference) << reference.message();
        const std::vector<uint16_t> samples = readSamples(dir + "/" + c.file, c.width, c.height);
        const std::vector<double> decoded = decodeAsEngine(c.engine, j, samples, c.width, c.height);
        const double step = j["height_step_m"].get<double>();
        double worst = 0.0;
        for (size_t i = 0; i < decoded.size(); ++i) worst = std::max(worst, std::fabs(decoded[i] - reference->field.heights[i]));
        std::printf("%s: %dx%d, worst round-trip error %.4f m, one step %.4f m\n", c.engine, c.width, c.height, worst, step);
        EXPECT_LE(worst, step) << c.engine;
        // Splat masks beside the heightmap, one per type, of its size, summing to 255.
        const auto& masks = j["heightmaps"][0]["masks"];
        ASSERT_GE(masks.size(), 2u) << c.engine;
        std::vector<int> sum(size_t(c.width) * c.height, 0);
        for (const auto& m : masks) {
            auto png = readPng8(dir + "/" + m.get<std::string>());
            ASSERT_TRUE(png) << png.message();
            ASSERT_EQ(png->width, c.width);
            ASSERT_EQ(png->height, c.height);
            for (size_t i = 0; i < sum.size(); ++i) sum[i] += png->samples[i];
        }
        for (size_t i = 0; i < sum.size(); i += 31) ASSERT_EQ(sum[i], 255) << c.engine << " pixel " << i;
    }
}
