// Private pieces of exportGltf (runtime/src/export): the meshed tiles, their packing into glTF
// attribute arrays, the tinygltf model and the file writer. One file per step.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "terrasynth/gltf_export.h"
#include "terrasynth/mesh.h"

namespace tinygltf {
class Model;
}

namespace terrasynth::export_detail {

// One tile of the region after meshing: quads [x0, x0+quads_x] x [y0, y0+quads_y] of region samples.
struct MeshedTile {
    int tx = 0, ty = 0;
    int x0 = 0, y0 = 0;
    int quads_x = 0, quads_y = 0;
    std::vector<TileMesh> lods;  // positions relative to the tile's north-west corner
    std::vector<uint8_t> types;  // (quads_x+1)*(quads_y+1) type ids, or empty
};

// How positions and colours are encoded; shared by every tile so shared edges stay identical.
struct PackingFrame {
    bool quantize = false;
    double quantum_m = 0.0;          // quantised position step (uniform on all axes)
    int64_t y_offset_quanta = 0;     // floor(min height / quantum), the same for every tile
    double mpp_x = 1.0, mpp_y = 1.0;
    int region_width = 2, region_height = 2;  // samples, for region-wide uvs
    float height_min = 0.0f, height_max = 1.0f;
    bool colors = false;
};

// Picks the quantum: the coarsest step that still fits the region's height range and the largest
// tile into 16 bits, snapped to spacing/k so grid positions are exact integers when spacing is square.
PackingFrame choosePackingFrame(bool quantize, double mpp_x, double mpp_y, int largest_tile_quads,
                                float height_min, float height_max);

// A glTF accessor's worth of data (attribute or indices), already laid out for its bufferView.
struct PackedArray {
    std::string semantic;          // POSITION, NORMAL, TEXCOORD_0, COLOR_0; "" for indices
    int component_type = 0;        // TINYGLTF_COMPONENT_TYPE_*
    int type = 0;                  // TINYGLTF_TYPE_*
    bool normalized = false;
    size_t count = 0;
    int byte_stride = 0;           // 0 for indices
    std::vector<uint8_t> bytes;
    std::vector<double> min, max;  // filled for POSITION
};

struct PackedPrimitive {
    std::vector<PackedArray> attributes;
    PackedArray indices;
};

struct PackedTile {
    int tx = 0, ty = 0;
    double translation[3] = {0, 0, 0};
    double scale = 1.0;  // uniform; 1 unless quantized
    std::vector<std::vector<PackedPrimitive>> lods;
    std::vector<float> lod_errors_m;
    double size_m = 0.0;  // the tile's larger side, for screen coverage
};

// Converts a meshed tile to glTF attribute arrays (Y-up) in `frame`'s encoding. Quantized tiles
// are split into primitives of at most 65535 vertices so their indices fit 16 bits.
PackedTile packTile(const MeshedTile& tile, const PackingFrame& frame);

// Where each array lands in the single binary buffer.
struct BinaryLayout {
    struct Block {
        const uint8_t* data;
        size_t size;
        size_t offset;  // 4-byte aligned; the gap before it is zero padding
    };
    std::vector<Block> blocks;  // in buffer order
    size_t total_bytes = 0;
};

struct ModelInputs {
    const GltfExportOptions* options = nullptr;
    const PackingFrame* frame = nullptr;
    const std::vector<PackedTile>* tiles = nullptr;
    int tiles_x = 0, tiles_y = 0;
    const std::string* texture_png = nullptr;  // empty or null: no texture
    int only_lod = -1;  // >= 0: every tile node holds this LOD alone, without MSFT_lod (LodLayout::Files)
};

// Fills `model` (nodes, meshes, accessors, bufferViews, material, extensions) and `layout`.
void buildModel(const ModelInputs& inputs, tinygltf::Model& model, BinaryLayout& layout);

// Serialises `model` (its buffer left empty) with tinygltf and stages GLB, or <stem>.bin then the
// .gltf, streaming `layout`'s blocks into the transaction's temporaries. Reports the bytes written.
Status stageGltfFiles(FileTransaction& transaction, const std::string& path, tinygltf::Model& model,
                      const BinaryLayout& layout, size_t* json_bytes, size_t* file_bytes);

// Runs body(i) for i in [0, n) on `threads` threads (the caller's among them), handing out indices
// in increasing order; stops handing out work after the first error and returns it.
Status parallelFor(int n, int threads, const std::function<Status(int)>& body);

}  // namespace terrasynth::export_detail
