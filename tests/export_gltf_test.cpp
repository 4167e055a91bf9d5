// glTF export of real DEMs: structure, heights, Y-up frame, LOD chain, seams, quantization, sizes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "terrasynth/gltf_export.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

const Heightfield& alaska() {
    static const Heightfield field = test::loadExemplarField("orom_alaska");
    return field;
}

GltfExportOptions regionOptions(int w, int h, int tile, int lods) {
    GltfExportOptions o;
    o.region = {100, 150, w, h};
    o.tile_size = tile;
    o.lods = lods;
    o.lod_layout = LodLayout::MsftLod;  // the tests below look at the MSFT_lod chain in one file
    o.threads = 2;
    return o;
}

tinygltf::Model load(const std::string& path) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool binary = path.size() > 4 && path.substr(path.size() - 4) == ".glb";
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    EXPECT_TRUE(ok) << err;
    return model;
}

// Reads component c of element i of an accessor as a double (dequantised when normalized).
double component(const tinygltf::Model& m, int accessor_index, size_t i, int c) {
    const tinygltf::Accessor& a = m.accessors[accessor_index];
    const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
    const int size = tinygltf::GetComponentSizeInBytes(a.componentType);
    const size_t stride = a.ByteStride(v);
    const uint8_t* p = &m.buffers[v.buffer].data[v.byteOffset + a.byteOffset + i * stride + c * size];
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); return a.normalized ? u / 65535.0 : u; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); return u; }
        case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t s; std::memcpy(&s, p, 1); return a.normalized ? std::max(s / 127.0, -1.0) : s; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return a.normalized ? *p / 255.0 : *p;
    }
    ADD_FAILURE() << "unexpected component type " << a.componentType;
    return 0.0;
}

struct WorldVertex {
    double x, y, z;  // glTF frame, metres
};

// World positions (node translation + scale * stored) of every vertex of a node's mesh.
std::vector<WorldVertex> worldVertices(const tinygltf::Model& m, int node_index) {
    const tinygltf::Node& node = m.nodes[node_index];
    const double s = node.scale.empty() ? 1.0 : node.scale[0];
    std::vector<WorldVertex> out;
    for (const tinygltf::Primitive& p : m.meshes[node.mesh].primitives) {
        const int pos = p.attributes.at("POSITION");
        for (size_t i = 0; i < m.accessors[pos].count; ++i)
            out.push_back({node.translation[0] + s * component(m, pos, i, 0), node.translation[1] + s * component(m, pos, i, 1),
                           node.translation[2] + s * component(m, pos, i, 2)});
    }
    return out;
}

int nodeNamed(const tinygltf::Model& m, const std::string& name) {
    for (size_t i = 0; i < m.nodes.size(); ++i)
        if (m.nodes[i].name == name) return int(i);
    ADD_FAILURE() << "no node " << name;
    return 0;
}

size_t fileSize(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? size_t(st.st_size) : 0;
}

}  // namespace

TEST(ExportGltf, DefaultLodLayoutWritesOneWholeTerrainPerFile) {
    const std::string dir = test::scratchDir("export_lod_files");
    GltfExportOptions options = regionOptions(161, 97, 64, 3);
    options.lod_layout = GltfExportOptions().lod_layout;  // the default
    ASSERT_EQ(options.lod_layout, LodLayout::Files);
    auto stats = exportGltf(dir + "/alaska.glb", heightSourceFromField(alaska()), options);
    ASSERT_TRUE(stats) << stats.message();
    ASSERT_EQ(stats->files, (std::vector<std::string>{dir + "/alaska.glb", dir + "/alaska_lod1.glb", dir + "/alaska_lod2.glb"}));
    size_t bytes = 0;
    for (int lod = 0; lod < 3; ++lod) {
        const tinygltf::Model m = load(stats->files[lod]);
        bytes += fileSize(stats->files[lod]);
        // The scene's root and its six tiles are every node: nothing for an importer to add.
        EXPECT_EQ(m.nodes.size(), 7u);
        EXPECT_EQ(m.nodes[m.scenes[0].nodes[0]].children.size(), 6u);
        EXPECT_TRUE(m.extensionsUsed.empty());
        EXPECT_EQ(m.nodes[0].extras.Get("lod").GetNumberAsInt(), lod);
        size_t vertices = 0;
        for (const tinygltf::Mesh& mesh : m.meshes)
            for (const tinygltf::Primitive& p : mesh.primitives) vertices += m.accessors[p.attributes.at("POSITION")].count;
        EXPECT_EQ(vertices, stats->lods[lod].vertices) << "LOD " << lod;
    }
    EXPECT_EQ(stats->file_bytes, bytes);
    EXPECT_EQ(gltfLodPath("a/b.GLTF", 2), "a/b_lod2.GLTF");
    EXPECT_EQ(gltfLodPath("a/b.glb", 0), "a/b.glb");
}

TEST(ExportGltf, WritesTilesWithLodChainYUpAndTrueHeights) {
    const std::string path = test::scratchDir("export_basic") + "/alaska.glb";
    auto stats = exportGltf(path, heightSourceFromField(alaska()), regionOptions(161, 97, 64, 3));
    ASSERT_TRUE(stats) << stats.message();
    EXPECT_EQ(stats->tiles_x, 3);  // 160 quads in tiles of 64
    EXPECT_EQ(stats->tiles_y, 2);  // 96 quads
    ASSERT_EQ(stats->lods.size(), 3u);
    // Shared edges repeat per tile; the two points where four tiles meet appear four times.
    EXPECT_EQ(stats->lods[0].vertices, 161u * 97u + 2u * 97u + 161u + 2u);
    EXPECT_GT(stats->lods[1].max_geometric_error_m, 1.0f);  // Alaska is rough
    EXPECT_EQ(stats->file_bytes, fileSize(path));

    const tinygltf::Model m = load(path);
    EXPECT_EQ(m.asset.version, "2.0");
    ASSERT_EQ(m.buffers.size(), 1u);
    ASSERT_EQ(m.scenes.size(), 1u);
    const tinygltf::Node& root = m.nodes[m.scenes[0].nodes[0]];
    ASSERT_EQ(root.children.size(), 6u);
    EXPECT_EQ(m.nodes.size(), 1u + 6u * 3u);
    EXPECT_NE(std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), "MSFT_lod"), m.extensionsUsed.end());

    const int tile = nodeNamed(m, "tile_1_1");
    const tinygltf::Value& lod = m.nodes[tile].extensions.at("MSFT_lod");
    ASSERT_EQ(lod.Get("ids").ArrayLen(), 2u);
    const tinygltf::Value& coverage = m.nodes[tile].extras.Get("MSFT_screencoverage");
    ASSERT_EQ(coverage.ArrayLen(), 3u);
    EXPECT_GT(coverage.Get(0).GetNumberAsDouble(), coverage.Get(1).GetNumberAsDouble());

    // Every LOD0 vertex of tile (1,1) sits on its sample: X east, Y = height, Z south.
    const double mpp = alaska().meters_per_pixel_x;
    for (const WorldVertex& v : worldVertices(m, tile)) {
        const int col = int(std::lround(v.x / mpp)), row = int(std::lround(v.z / mpp));
        ASSERT_NEAR(v.x, col * mpp, 1e-3);
        ASSERT_GE(col, 64);
        ASSERT_LE(col, 128);
        ASSERT_NEAR(v.y, alaska().at(100 + col, 150 + row), 1e-3);
    }
    // POSITION min/max are exact and normals unit.
    for (const tinygltf::Mesh& mesh : m.meshes) {
        for (const tinygltf::Primitive& p : mesh.primitives) {
            const tinygltf::Accessor& a = m.accessors[p.attributes.at("POSITION")];
            ASSERT_EQ(a.minValues.size(), 3u);
            double lo = INFINITY;
            for (size_t i = 0; i < a.count; ++i) lo = std::min(lo, component(m, p.attributes.at("POSITION"), i, 1));
            EXPECT_EQ(lo, a.minValues[1]);
            const int n = p.attributes.at("NORMAL");
            for (size_t i = 0; i < m.accessors[n].count; i += 7) {
                const double x = component(m, n, i, 0), y = component(m, n, i, 1), z = component(m, n, i, 2);
                ASSERT_NEAR(x * x + y * y + z * z, 1.0, 1e-5);
                ASSERT_GT(y, 0.0);  // up
            }
            // Small tiles need only 16-bit indices.
            EXPECT_EQ(m.accessors[p.indices].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
        }
    }
}

TEST(ExportGltf, NeighbouringTilesShareTheirEdgeAtEveryLodMix) {
    const std::string path = test::scratchDir("export_seams") + "/seams.glb";
    ASSERT_TRUE(exportGltf(path, heightSourceFromField(alaska()), regionOptions(129, 65, 64, 4)));
    const tinygltf::Model m = load(path);
    const double edge_x = 64 * alaska().meters_per_pixel_x;
    auto edge = [&](int node) {
        std::map<long, double> heights;  // by Z in mm
        for (const WorldVertex& v : worldVertices(m, node))
            if (std::fabs(v.x - edge_x) < 1e-3) heights[std::lround(v.z * 1000)] = v.y;
        return heights;
    };
    const int west = nodeNamed(m, "tile_0_0"), east = nodeNamed(m, "tile_1_0");
    const auto reference = edge(west);
    ASSERT_EQ(reference.size(), 65u);
    for (int lod = 1; lod < 4; ++lod) {
        const auto coarse = edge(nodeNamed(m, "tile_1_0_lod" + std::to_string(lod)));
        ASSERT_EQ(coarse.size(), reference.size()) << "lod " << lod;
        for (const auto& [z, y] : reference) EXPECT_NEAR(coarse.at(z), y, 1e-3) << "lod " << lod;
    }
    EXPECT_EQ(edge(east), reference);
}

TEST(ExportGltf, QuantizedIsSmallerAlignedAndStillCrackFree) {
    const std::string dir = test::scratchDir("export_quantized");
    GltfExportOptions options = regionOptions(513, 385, 256, 3);  // LOD0 tiles need 32-bit unquantized
    ASSERT_TRUE(exportGltf(dir + "/plain.glb", heightSourceFromField(alaska()), options));
    options.quantize = true;
    auto stats = exportGltf(dir + "/quantized.glb", heightSourceFromField(alaska()), options);
    ASSERT_TRUE(stats) << stats.message();
    const double ratio = double(fileSize(dir + "/quantized.glb")) / fileSize(dir + "/plain.glb");
    std::printf("quantized / plain size: %.3f\n", ratio);
    EXPECT_LE(ratio, 0.60);

    const tinygltf::Model m = load(dir + "/quantized.glb");
    ASSERT_EQ(m.extensionsRequired, std::vector<std::string>{"KHR_mesh_quantization"});
    for (const tinygltf::Accessor& a : m.accessors) {
        const tinygltf::BufferView& v = m.bufferViews[a.bufferView];
        EXPECT_EQ(v.byteOffset % 4, 0u);
        if (v.target == TINYGLTF_TARGET_ARRAY_BUFFER) {
            EXPECT_EQ(a.ByteStride(v) % 4, 0);
        }
        if (v.target == TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER) {
            EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
        }
    }
    // Dequantised heights stay within half a quantum (plus float slack) of the DEM.
    const double mpp = alaska().meters_per_pixel_x, q = stats->quantum_m;
    ASSERT_GT(q, 0.0);
    const int tile = nodeNamed(m, "tile_0_0");  // 257x257 vertices: split for 16-bit indices
    EXPECT_GT(m.meshes[m.nodes[tile].mesh].primitives.size(), 1u);
    for (const WorldVertex& v : worldVertices(m, tile)) {
        const int col = int(std::lround(v.x / mpp)), row = int(std::lround(v.z / mpp));
        ASSERT_NEAR(v.y, alaska().at(100 + col, 150 + row), 0.5 * q + 1e-3);
    }
    // A vertex shared by tiles (0,0) and (1,0) dequantises identically in both, whatever their LODs.
    std::map<long, double> west, east;
    for (const WorldVertex& v : worldVertices(m, tile))
        if (std::fabs(v.x - 256 * mpp) < 0.5 * q) west[std::lround(v.z / q)] = v.y;
    for (const WorldVertex& v : worldVertices(m, nodeNamed(m, "tile_1_0_lod2")))
        if (std::fabs(v.x - 256 * mpp) < 0.5 * q) east[std::lround(v.z / q)] = v.y;
    ASSERT_EQ(west.size(), 257u);
    EXPECT_EQ(west, east);
}

TEST(ExportGltf, GltfWithSidecarBinColoursAndTexture) {
    const std::string dir = test::scratchDir("export_gltf_text");
    GltfExportOptions options = regionOptions(100, 80, 32, 2);
    options.vertex_colors = true;
    options.texture_size = 64;
    // Types from height bands of the real DEM stand in for a coordinate map here.
    const Heightfield& field = alaska();
    options.types = [&field](const PixelWindow& w, int) -> Result<std::vector<uint8_t>> {
        std::vector<uint8_t> t(size_t(w.width) * w.height);
        for (int y = 0; y < w.height; ++y)
            for (int x = 0; x < w.width; ++x) t[size_t(y) * w.width + x] = field.at(int(w.x) + x, int(w.y) + y) > 1500.0f;
        return t;
    };
    auto stats = exportGltf(dir + "/terrain.gltf", heightSourceFromField(field), options);
    ASSERT_TRUE(stats) << stats.message();
    EXPECT_EQ(fileSize(dir + "/terrain.bin"), stats->binary_bytes);
    const tinygltf::Model m = load(dir + "/terrain.gltf");
    ASSERT_EQ(m.images.size(), 1u);
    EXPECT_EQ(m.images[0].width, 64);
    EXPECT_EQ(m.images[0].height, 51);
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].pbrMetallicRoughness.baseColorTexture.index, 0);
    const tinygltf::Primitive& p = m.meshes[0].primitives[0];
    ASSERT_TRUE(p.attributes.count("COLOR_0"));
    // Two types give visibly different colours somewhere.
    std::set<double> reds;
    for (size_t i = 0; i < m.accessors[p.attributes.at("COLOR_0")].count; ++i) reds.insert(component(m, p.attributes.at("COLOR_0"), i, 0));
    EXPECT_GT(reds.size(), 10u);
    // Region-wide uvs: the tile at (0,0) starts at uv 0.
    const int uv = p.attributes.at("TEXCOORD_0");
    double min_u = 1.0;
    for (size_t i = 0; i < m.accessors[uv].count; ++i) min_u = std::min(min_u, component(m, uv, i, 0));
    EXPECT_EQ(min_u, 0.0);
}

TEST(ExportGltf, ErrorsNameTheProblem) {
    const std::string dir = test::scratchDir("export_errors");
    GltfExportOptions options = regionOptions(64, 64, 0, 1);
    auto bad_tile = exportGltf(dir + "/x.glb", heightSourceFromField(alaska()), options);
    ASSERT_FALSE(bad_tile);
    EXPECT_NE(bad_tile.message().find("tile_size"), std::string::npos);

    options.tile_size = 32;
    HeightSource failing = [](const PixelWindow&, int) -> Result<Heightfield> { return Status::error("synthesis failed"); };
    auto failed = exportGltf(dir + "/x.glb", failing, options);
    ASSERT_FALSE(failed);
    EXPECT_NE(failed.message().find("synthesis failed"), std::string::npos);
    EXPECT_NE(failed.message().find("window"), std::string::npos);

    auto bad_ext = exportGltf(dir + "/x.obj", heightSourceFromField(alaska()), options);
    ASSERT_FALSE(bad_ext);
    EXPECT_NE(bad_ext.message().find(".glb or .gltf"), std::string::npos);

    // A missing folder is made for the file; a file where the folder should be is named.
    std::ofstream(dir + "/in_the_way") << "a file";
    auto bad_dir = exportGltf(dir + "/in_the_way/x.glb", heightSourceFromField(alaska()), options);
    ASSERT_FALSE(bad_dir);
    EXPECT_NE(bad_dir.message().find("in_the_way/x.glb"), std::string::npos) << bad_dir.message();
    EXPECT_EQ(fileSize(dir + "/x.glb"), 0u);  // nothing half-written
}
