// Every kind of glTF file the exporter writes passes the Khronos glTF validator with zero errors.
// Needs node and `npm ci --prefix scripts`; skipped only when node itself is absent.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "terrasynth/gltf_export.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

std::string repoDir() { return test::dataDir() + "/.."; }

// Runs scripts/validate_gltf.sh; returns its exit code and output.
int validate(const std::string& file, std::string* output) {
    const std::string log = file + ".validation.txt";
    const std::string cmd = "'" + repoDir() + "/scripts/validate_gltf.sh' '" + file + "' > '" + log + "' 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    *output = text.str();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class ExportValidator : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::system("command -v node > /dev/null 2>&1") != 0) GTEST_SKIP() << "node is not installed";
        std::ifstream installed(repoDir() + "/scripts/node_modules/gltf-validator/package.json");
        ASSERT_TRUE(installed.good()) << "gltf-validator is not installed: run `npm ci --prefix scripts` in the repository";
    }

    void exportAndValidate(const std::string& name, GltfExportOptions options, const std::string& stem) {
        const std::string path = test::scratchDir("validator_" + name) + "/" + name;
        static const Heightfield field = test::loadExemplarField(stem);
        auto stats = exportGltf(path, heightSourceFromField(field), options);
        ASSERT_TRUE(stats) << stats.message();
        std::string output;
        const int code = validate(path, &output);
        EXPECT_EQ(code, 0) << output;
        EXPECT_NE(output.find(" 0 errors"), std::string::npos) << output;
    }
};

GltfExportOptions base(int w, int h, int tile, int lods) {
    GltfExportOptions o;
    o.region = {37, 51, w, h};
    o.tile_size = tile;
    o.lods = lods;
    o.lod_layout = LodLayout::MsftLod;  // every LOD in the one file validated
    return o;
}

}  // namespace

TEST_F(ExportValidator, PlainGlbWithLods) { exportAndValidate("plain.glb", base(300, 200, 128, 3), "orom_alaska"); }

TEST_F(ExportValidator, LodFiles) {
    const std::string dir = test::scratchDir("validator_lod_files");
    static const Heightfield field = test::loadExemplarField("orom_alaska");
    GltfExportOptions o = base(300, 200, 128, 3);
    o.lod_layout = LodLayout::Files;
    auto stats = exportGltf(dir + "/files.glb", heightSourceFromField(field), o);
    ASSERT_TRUE(stats) << stats.message();
    ASSERT_EQ(stats->files.size(), 3u);
    for (const std::string& file : stats->files) {
        std::string output;
        EXPECT_EQ(validate(file, &output), 0) << output;
        EXPECT_NE(output.find(" 0 errors"), std::string::npos) << output;
    }
}

TEST_F(ExportValidator, LargeTilesWith32BitIndices) {
    exportAndValidate("wide.glb", base(400, 300, 300, 2), "orom_rockies");
}

TEST_F(ExportValidator, QuantizedGlb) {
    GltfExportOptions o = base(300, 300, 256, 4);
    o.quantize = true;
    exportAndValidate("quantized.glb", o, "orom_himalaya-everest");
}

TEST_F(ExportValidator, GltfWithBinColoursTextureAndSimplifiedLods) {
    GltfExportOptions o = base(200, 150, 64, 3);
    o.vertex_colors = true;
    o.texture_size = 128;
    o.lod_method = LodMethod::Simplify;
    o.quantize = true;
    exportAndValidate("textured.gltf", o, "orom_appalachians");
}

TEST_F(ExportValidator, AnisotropicSpacing) {
    GltfExportOptions o = base(150, 120, 64, 2);
    o.quantize = true;
    exportAndValidate("fuji.glb", o, "osge_mt_fuji_90m");
}

TEST_F(ExportValidator, ValidatorRejectsABrokenFile) {
    // The check has teeth: a GLB whose binary chunk is cut short fails validation.
    const std::string dir = test::scratchDir("validator_broken");
    static const Heightfield field = test::loadExemplarField("orom_alaska");
    ASSERT_TRUE(exportGltf(dir + "/whole.glb", heightSourceFromField(field), base(100, 100, 64, 1)));
    std::ifstream in(dir + "/whole.glb", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir + "/broken.glb", std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
    std::string output;
    EXPECT_EQ(validate(dir + "/broken.glb", &output), 1) << output;
}
