// One tile of a bake as a .glb: the mesher's grid with a skirt, packed and modelled by the exporter's
// steps (packTile, buildModel, stageGltfFiles), placed in the world by the root node, and described in
// the root node's extras for the merge.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "core/json_reader.h"
#include "export/export_internal.h"
#include "terrasynth/file_transaction.h"
#include "export/tileset_plan.h"

namespace terrasynth::bake_detail {

using namespace export_detail;

namespace {

// World bounds (x east, y north, z up) of the packed positions, after the tile node's and the root
// node's transforms: glTF (X, Y, Z) is world (X, -Z, Y).
void contentBounds(const PackedTile& packed, const double root[3], double bounds[6]) {
    for (int c = 0; c < 3; ++c) bounds[c] = INFINITY, bounds[3 + c] = -INFINITY;
    for (const PackedPrimitive& prim : packed.lods[0]) {
        const PackedArray& pos = prim.attributes.front();  // POSITION comes first
        if (pos.min.size() != 3) continue;
        double lo[3], hi[3];
        for (int c = 0; c < 3; ++c) {
            lo[c] = root[c] + packed.translation[c] + packed.scale * pos.min[c];
            hi[c] = root[c] + packed.translation[c] + packed.scale * pos.max[c];
        }
        const double world_lo[3] = {lo[0], -hi[2], lo[1]}, world_hi[3] = {hi[0], -lo[2], hi[1]};
        for (int c = 0; c < 3; ++c) bounds[c] = std::min(bounds[c], world_lo[c]), bounds[3 + c] = std::max(bounds[3 + c], world_hi[c]);
    }
}

tinygltf::Value numberArray(const double* v, int n) {
    tinygltf::Value::Array a;
    for (int k = 0; k < n; ++k) a.push_back(tinygltf::Value(v[k]));
    return tinygltf::Value(a);
}

}  // namespace

Result<TileRecord> writeTileGlb(const std::string& path, const BakeTree& tree, const TileKey& key,
                                const Heightfield& field, int border, bool quantize) {
    const SampleSpan span = tree.samples(key);
    const int level = BakeTree::sourceLevel(key.lod), step = BakeTree::meshStep(key.lod);
    if (field.width != span.quadsX() + 1 + 2 * border || field.height != span.quadsY() + 1 + 2 * border)
        return Status::error(path + ": internal: tile field does not match its span");

    MeshOptions mesh_options;
    mesh_options.step = step;
    mesh_options.border = border;
    mesh_options.optimize_order = true;
    mesh_options.skirt_depth_m = skirtDepth(field, border, step * field.meters_per_pixel_x);
    MeshedTile tile;
    tile.tx = static_cast<int>(tree.implicitOf(key).x), tile.ty = static_cast<int>(tree.implicitOf(key).y);
    tile.quads_x = span.quadsX(), tile.quads_y = span.quadsY();
    tile.lods.push_back(meshHeightfield(field, mesh_options));
    const TileMesh& mesh = tile.lods.front();

    float lo = INFINITY, hi = -INFINITY;
    for (size_t v = 0; v < mesh.vertexCount(); ++v) lo = std::min(lo, mesh.positions[3 * v + 2]), hi = std::max(hi, mesh.positions[3 * v + 2]);
    // The quantum follows from the full tile's extent, so every tile of a LOD shares it (and their
    // shared edges stay identical) unless a tile's relief outgrows the extent.
    PackingFrame frame = choosePackingFrame(quantize, field.meters_per_pixel_x, field.meters_per_pixel_y,
                                            tree.tileSize() * step, lo, hi);
    frame.region_width = tile.quads_x + 1, frame.region_height = tile.quads_y + 1;  // uvs over the tile
    const PackedTile packed = packTile(tile, frame);

    GltfExportOptions model_options;
    model_options.region = {span.x0, span.y0, tile.quads_x + 1, tile.quads_y + 1};
    model_options.level = level;
    model_options.tile_size = tree.tileSize();
    model_options.lods = 1;
    model_options.quantize = quantize;
    const std::vector<PackedTile> tiles{packed};
    tinygltf::Model model;
    BinaryLayout layout;
    buildModel({&model_options, &frame, &tiles, 1, 1, nullptr}, model, layout);

    const double spacing = field.meters_per_pixel_x;
    const double root[3] = {span.x0 * spacing, 0.0, span.y0 * spacing};
    TileRecord record;
    record.key = key;
    record.own_error_m = mesh.geometric_error_m;
    contentBounds(packed, root, record.bounds);

    tinygltf::Node& root_node = model.nodes[0];
    root_node.translation = {root[0], root[1], root[2]};
    const ImplicitCoord c = tree.implicitOf(key);
    tinygltf::Value::Object info;
    info["lod"] = tinygltf::Value(key.lod);
    // BakeTree keeps every index and coordinate within 2^31 (checkBakeOptions bounds the tree).
    info["index"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(int(key.i)), tinygltf::Value(int(key.j))});
    info["implicit"] = tinygltf::Value(
        tinygltf::Value::Array{tinygltf::Value(c.depth), tinygltf::Value(int(c.x)), tinygltf::Value(int(c.y))});
    info["source_level"] = tinygltf::Value(level);
    info["step"] = tinygltf::Value(step);
    info["geometric_error_m"] = tinygltf::Value(double(record.own_error_m));
    info["skirt_depth_m"] = tinygltf::Value(double(mesh_options.skirt_depth_m));
    info["bounds"] = numberArray(record.bounds, 6);
    tinygltf::Value::Object extras;
    extras["terrasynth_tile"] = tinygltf::Value(info);
    extras["frame"] = tinygltf::Value(std::string(
        "world frame of the global grid: level-0 sample (0,0) at the origin; X east, Y up, Z south; metres"));
    extras["meters_per_pixel"] = tinygltf::Value(spacing);
    root_node.extras = tinygltf::Value(extras);

    size_t json_bytes = 0, file_bytes = 0;
    FileTransaction transaction;
    if (Status s = stageGltfFiles(transaction, path, model, layout, &json_bytes, &file_bytes); !s) return s;
    if (Status s = transaction.commit(); !s) return s;
    record.file_bytes = static_cast<int64_t>(file_bytes);
    return record;
}

namespace {

uint32_t le32(const unsigned char* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

}  // namespace

bool glbComplete(const std::string& path) {
    struct stat st;
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size < 20) return false;
    std::ifstream in(path, std::ios::binary);
    unsigned char header[12];
    if (!in.read(reinterpret_cast<char*>(header), 12)) return false;
    return le32(header) == 0x46546C67u && le32(header + 8) == static_cast<uint64_t>(st.st_size);
}

Result<TileRecord> tileRecordFromGlb(const std::string& bytes, const std::string& path) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    const size_t size = bytes.size();
    if (size < 20 || le32(p) != 0x46546C67u) return Status::error(path + ": not a GLB file");
    if (le32(p + 4) != 2) return Status::error(path + ": GLB version " + std::to_string(le32(p + 4)) + ", not 2");
    if (le32(p + 8) != size)
        return Status::error(path + ": the header says " + std::to_string(le32(p + 8)) + " bytes, the file has " +
                             std::to_string(size) + " (truncated or padded)");
    // Chunk lengths are compared with what is left, never added up first (no wrap-around).
    const uint64_t json_length = le32(p + 12);
    if (le32(p + 16) != 0x4E4F534Au || json_length % 4 != 0 || json_length > size - 20)
        return Status::error(path + ": the first chunk is not a JSON chunk inside the file");
    const size_t bin_at = 20 + static_cast<size_t>(json_length);
    if (size - bin_at < 8 || le32(p + bin_at + 4) != 0x004E4942u)
        return Status::error(path + ": no BIN chunk after the JSON chunk");
    const uint64_t bin_length = le32(p + bin_at);
    if (bin_length % 4 != 0 || bin_length != size - bin_at - 8)
        return Status::error(path + ": the BIN chunk's length " + std::to_string(bin_length) + " does not end at the end of the file");
    auto parsed = detail::parseJson(bytes.substr(20, json_length), path + ": JSON chunk");
    if (!parsed) return parsed.status();
    const nlohmann::json& j = *parsed;
    TileRecord r;
    try {
        const uint64_t buffer = j.at("buffers").at(0).at("byteLength").get<uint64_t>();
        if (buffer > bin_length) return Status::error(path + ": the buffer is larger than the BIN chunk");
        const auto& info = j.at("nodes").at(0).at("extras").at("terrasynth_tile");
        r.key.lod = info.at("lod").get<int>();
        r.key.i = info.at("index").at(0).get<int64_t>();
        r.key.j = info.at("index").at(1).get<int64_t>();
        r.own_error_m = info.at("geometric_error_m").get<double>();
        for (int k = 0; k < 6; ++k) r.bounds[k] = info.at("bounds").at(k).get<double>();
    } catch (const nlohmann::json::exception&) {
        return Status::error(path + ": not a terrasynth bake tile (no buffer or no terrasynth_tile extras)");
    }
    if (!std::isfinite(r.own_error_m) || r.own_error_m < 0.0) return Status::error(path + ": geometric_error_m is not a finite error");
    for (double b : r.bounds)
        if (!std::isfinite(b)) return Status::error(path + ": bounds are not finite");
    r.file_bytes = static_cast<int64_t>(size);
    return r;
}

}  // namespace terrasynth::bake_detail
