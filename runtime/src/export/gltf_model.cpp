// The tinygltf model of an export: one node per tile (MSFT_lod for coarser LODs, or one LOD per
// model), one buffer.
#include <tiny_gltf.h>

#include <algorithm>
#include <cstdio>

#include "export/export_internal.h"

namespace terrasynth::export_detail {

namespace {

class ModelBuilder {
public:
    ModelBuilder(tinygltf::Model& model, BinaryLayout& layout) : model_(model), layout_(layout) {}

    int addBlock(const uint8_t* data, size_t size, int target, int stride) {
        const size_t offset = (layout_.total_bytes + 3) & ~size_t(3);
        layout_.blocks.push_back({data, size, offset});
        layout_.total_bytes = offset + size;
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = offset;
        view.byteLength = size;
        view.byteStride = static_cast<size_t>(stride);
        view.target = target;
        model_.bufferViews.push_back(view);
        return static_cast<int>(model_.bufferViews.size() - 1);
    }

    int addAccessor(const PackedArray& a) {
        const bool vertex = !a.semantic.empty();
        tinygltf::Accessor accessor;
        accessor.bufferView = addBlock(a.bytes.data(), a.bytes.size(),
                                       vertex ? TINYGLTF_TARGET_ARRAY_BUFFER : TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER,
                                       vertex ? a.byte_stride : 0);
        accessor.componentType = a.component_type;
        accessor.type = a.type;
        accessor.normalized = a.normalized;
        accessor.count = a.count;
        accessor.minValues = a.min;
        accessor.maxValues = a.max;
        model_.accessors.push_back(accessor);
        return static_cast<int>(model_.accessors.size() - 1);
    }

    int addMesh(const std::vector<PackedPrimitive>& prims, const std::string& name, int material) {
        tinygltf::Mesh mesh;
        mesh.name = name;
        for (const PackedPrimitive& p : prims) {
            tinygltf::Primitive primitive;
            for (const PackedArray& a : p.attributes) primitive.attributes[a.semantic] = addAccessor(a);
            primitive.indices = addAccessor(p.indices);
            primitive.mode = TINYGLTF_MODE_TRIANGLES;
            primitive.material = material;
            mesh.primitives.push_back(std::move(primitive));
        }
        model_.meshes.push_back(std::move(mesh));
        return static_cast<int>(model_.meshes.size() - 1);
    }

    int addNode(const std::string& name, int mesh, const PackedTile& tile) {
        tinygltf::Node node;
        node.name = name;
        node.mesh = mesh;
        node.translation = {tile.translation[0], tile.translation[1], tile.translation[2]};
        if (tile.scale != 1.0) node.scale = {tile.scale, tile.scale, tile.scale};
        model_.nodes.push_back(std::move(node));
        return static_cast<int>(model_.nodes.size() - 1);
    }

    int addMaterial(int texture) {
        tinygltf::Material material;
        material.name = "terrain";
        material.pbrMetallicRoughness.metallicFactor = 0.0;
        material.pbrMetallicRoughness.roughnessFactor = 1.0;
        if (texture >= 0) material.pbrMetallicRoughness.baseColorTexture.index = texture;
        model_.materials.push_back(std::move(material));
        return static_cast<int>(model_.materials.size() - 1);
    }

    int addTexture(const std::string& png) {
        tinygltf::Image image;
        image.name = "terrain_tint";
        image.mimeType = "image/png";
        image.bufferView = addBlock(reinterpret_cast<const uint8_t*>(png.data()), png.size(), 0, 0);
        model_.images.push_back(std::move(image));
        tinygltf::Sampler sampler;
        sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
        sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
        sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        model_.samplers.push_back(sampler);
        tinygltf::Texture texture;
        texture.source = static_cast<int>(model_.images.size() - 1);
        texture.sampler = static_cast<int>(model_.samplers.size() - 1);
        model_.textures.push_back(texture);
        return static_cast<int>(model_.textures.size() - 1);
    }

private:
    tinygltf::Model& model_;
    BinaryLayout& layout_;
};

// MSFT_screencoverage thresholds: LOD k serves while the tile covers at least this fraction of the
// viewport height, i.e. until LOD k+1's geometric error would stay under ~2 pixels of a 1080-pixel
// view. Strictly decreasing; the last entry 0 keeps the coarsest LOD to any distance.
std::vector<double> screenCoverage(const PackedTile& tile) {
    const size_t n = tile.lods.size();
    std::vector<double> coverage(n, 0.0);
    const double pixels_per_view = 1080.0, tolerated_pixels = 2.0;
    for (size_t k = 0; k + 1 < n; ++k) {
        const double coarser_error = std::max<double>(tile.lod_errors_m[k + 1], 1e-3);
        coverage[k] = std::min(1.0, tolerated_pixels / pixels_per_view * tile.size_m / coarser_error);
    }
    for (size_t k = n - 1; k-- > 0;) coverage[k] = std::max(coverage[k], coverage[k + 1] * 1.0001 + 1e-9);
    return coverage;
}

}  // namespace

void buildModel(const ModelInputs& in, tinygltf::Model& model, BinaryLayout& layout) {
    const GltfExportOptions& options = *in.options;
    ModelBuilder builder(model, layout);
    model.asset.version = "2.0";
    model.asset.generator = "terrasynth";
    if (options.quantize) {
        model.extensionsUsed.push_back("KHR_mesh_quantization");
        model.extensionsRequired.push_back("KHR_mesh_quantization");
    }
    const bool msft_lod = options.lods > 1 && in.only_lod < 0;
    if (msft_lod) model.extensionsUsed.push_back("MSFT_lod");

    const int texture = in.texture_png && !in.texture_png->empty() ? builder.addTexture(*in.texture_png) : -1;
    const int material = builder.addMaterial(texture);

    tinygltf::Node root;
    root.name = "terrain";
    tinygltf::Value::Object extras;
    extras["meters_per_pixel_x"] = tinygltf::Value(in.frame->mpp_x);
    extras["meters_per_pixel_y"] = tinygltf::Value(in.frame->mpp_y);
    extras["region"] = tinygltf::Value(tinygltf::Value::Array{
        tinygltf::Value(static_cast<double>(options.region.x)), tinygltf::Value(static_cast<double>(options.region.y)),
        tinygltf::Value(options.region.width), tinygltf::Value(options.region.height)});
    extras["level"] = tinygltf::Value(options.level);
    extras["tile_size"] = tinygltf::Value(options.tile_size);
    if (in.only_lod >= 0) extras["lod"] = tinygltf::Value(in.only_lod);
    extras["frame"] = tinygltf::Value(std::string("origin at the region's north-west corner; X east, Y up, Z south; metres"));
    root.extras = tinygltf::Value(extras);
    model.nodes.push_back(root);

    char name[64];
    for (const PackedTile& tile : *in.tiles) {
        std::snprintf(name, sizeof name, "tile_%d_%d", tile.tx, tile.ty);
        const int node = builder.addNode(name, builder.addMesh(tile.lods[std::max(0, in.only_lod)], name, material), tile);
        model.nodes[0].children.push_back(node);
        if (!msft_lod) continue;
        tinygltf::Value::Array ids;
        for (size_t k = 1; k < tile.lods.size(); ++k) {
            std::snprintf(name, sizeof name, "tile_%d_%d_lod%zu", tile.tx, tile.ty, k);
            // LOD nodes stay outside the scene graph; MSFT_lod reaches them from the tile node.
            ids.push_back(tinygltf::Value(builder.addNode(name, builder.addMesh(tile.lods[k], name, material), tile)));
        }
        tinygltf::Value::Object lod;
        lod["ids"] = tinygltf::Value(ids);
        model.nodes[node].extensions["MSFT_lod"] = tinygltf::Value(lod);
        tinygltf::Value::Array coverage, errors;
        for (double c : screenCoverage(tile)) coverage.push_back(tinygltf::Value(c));
        for (float e : tile.lod_errors_m) errors.push_back(tinygltf::Value(static_cast<double>(e)));
        tinygltf::Value::Object node_extras;
        node_extras["MSFT_screencoverage"] = tinygltf::Value(coverage);
        node_extras["geometric_error_m"] = tinygltf::Value(errors);
        model.nodes[node].extras = tinygltf::Value(node_extras);
    }

    tinygltf::Scene scene;
    scene.name = "terrain";
    scene.nodes.push_back(0);
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    model.buffers.emplace_back();  // data streamed by writeGltfFiles
}

}  // namespace terrasynth::export_detail
