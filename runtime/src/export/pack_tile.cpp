// Packing a meshed tile into glTF arrays: Y-up, float or KHR_mesh_quantization encodings, index width
// as needed (quantized primitives split to stay under 65536 vertices).
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "export/colors.h"
#include "export/export_internal.h"

namespace terrasynth::export_detail {

PackingFrame choosePackingFrame(bool quantize, double mpp_x, double mpp_y, int largest_tile_quads,
                                float height_min, float height_max) {
    PackingFrame frame;
    frame.quantize = quantize;
    frame.mpp_x = mpp_x, frame.mpp_y = mpp_y;
    frame.height_min = height_min, frame.height_max = height_max;
    if (!quantize) return frame;
    // 65533 leaves room for rounding the tile offset and the height floor.
    const double range = std::max(0.0, static_cast<double>(height_max) - height_min);
    double q = std::max({range / 65533.0, largest_tile_quads * std::max(mpp_x, mpp_y) / 65533.0, 1e-6});
    if (mpp_x == mpp_y && q <= mpp_x) q = mpp_x / std::floor(mpp_x / q);  // grid points on whole quanta
    frame.quantum_m = q;
    frame.y_offset_quanta = static_cast<int64_t>(std::floor(height_min / q));
    return frame;
}

namespace {

// Splits triangles into chunks of at most `limit` distinct vertices, keeping their order (which the
// mesher optimised for the vertex cache). Returns per chunk its vertices and local indices.
struct Chunk {
    std::vector<uint32_t> vertices;
    std::vector<uint32_t> indices;
};
std::vector<Chunk> splitByVertexCount(const TileMesh& mesh, size_t limit) {
    std::vector<Chunk> chunks;
    if (mesh.vertexCount() <= limit) {
        Chunk all;
        all.vertices.resize(mesh.vertexCount());
        for (size_t v = 0; v < all.vertices.size(); ++v) all.vertices[v] = static_cast<uint32_t>(v);
        all.indices = mesh.indices;
        chunks.push_back(std::move(all));
        return chunks;
    }
    std::vector<uint32_t> local(mesh.vertexCount(), ~0u);
    Chunk current;
    auto flush = [&] {
        for (uint32_t v : current.vertices) local[v] = ~0u;
        chunks.push_back(std::move(current));
        current = Chunk();
    };
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        size_t fresh = 0;
        for (int k = 0; k < 3; ++k) fresh += local[mesh.indices[t + k]] == ~0u;
        if (current.vertices.size() + fresh > limit) flush();
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = mesh.indices[t + k];
            if (local[v] == ~0u) {
                local[v] = static_cast<uint32_t>(current.vertices.size());
                current.vertices.push_back(v);
            }
            current.indices.push_back(local[v]);
        }
    }
    if (!current.indices.empty()) flush();
    return chunks;
}

template <class T>
void put(std::vector<uint8_t>& bytes, size_t offset, T value) {
    std::memcpy(&bytes[offset], &value, sizeof(T));
}

PackedArray makeArray(const char* semantic, int component, int type, bool normalized, size_t count, int stride) {
    PackedArray a;
    a.semantic = semantic;
    a.component_type = component;
    a.type = type;
    a.normalized = normalized;
    a.count = count;
    a.byte_stride = stride;
    a.bytes.assign(count * stride, 0);
    return a;
}

void trackMinMax(PackedArray& a, const double* v) {
    if (a.min.empty()) {
        a.min.assign(v, v + 3);
        a.max.assign(v, v + 3);
        return;
    }
    for (int c = 0; c < 3; ++c) a.min[c] = std::min(a.min[c], v[c]), a.max[c] = std::max(a.max[c], v[c]);
}


// The quantized normal whose dequantised direction is closest to unit length and to `n`: the nearest
// rounding can miss unit length by ~1%, so try the neighbouring roundings too.
void quantizeNormal(const float* n, int8_t* out) {
    int nearest[3];
    for (int c = 0; c < 3; ++c) nearest[c] = static_cast<int>(std::nearbyint(n[c] * 127.0f));
    const int len2 = nearest[0] * nearest[0] + nearest[1] * nearest[1] + nearest[2] * nearest[2];
    if (std::abs(len2 - 127 * 127) <= 80) {  // within 0.25% of unit length: the usual case
        for (int c = 0; c < 3; ++c) out[c] = static_cast<int8_t>(nearest[c]);
        return;
    }
    double best = std::numeric_limits<double>::max();
    const float scaled[3] = {n[0] * 127.0f, n[1] * 127.0f, n[2] * 127.0f};
    for (int mask = 0; mask < 8; ++mask) {
        int q[3];
        for (int c = 0; c < 3; ++c) {
            q[c] = static_cast<int>(((mask >> c) & 1) ? std::ceil(scaled[c]) : std::floor(scaled[c]));
            q[c] = std::clamp(q[c], -127, 127);
        }
        const double len = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2]) / 127.0;
        const double dir = std::fabs(q[0] / 127.0 - n[0]) + std::fabs(q[1] / 127.0 - n[1]) + std::fabs(q[2] / 127.0 - n[2]);
        const double score = std::fabs(len - 1.0) * 4.0 + dir;
        if (score < best) best = score, out[0] = int8_t(q[0]), out[1] = int8_t(q[1]), out[2] = int8_t(q[2]);
    }
}

// Round half away from zero, as llround, without its libm call in the per-vertex loop.
inline int64_t roundToInt(double v) { return static_cast<int64_t>(v < 0.0 ? v - 0.5 : v + 0.5); }

uint16_t unorm16(double v) { return static_cast<uint16_t>(std::clamp(v, 0.0, 1.0) * 65535.0 + 0.5); }

PackedPrimitive packChunk(const MeshedTile& tile, const TileMesh& mesh, const Chunk& chunk, const PackingFrame& f,
                          const PackedTile& placed) {
    const size_t n = chunk.vertices.size();
    PackedPrimitive prim;
    const bool q = f.quantize;
    PackedArray pos = q ? makeArray("POSITION", TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, false, n, 8)
                        : makeArray("POSITION", TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false, n, 12);
    PackedArray nor = q ? makeArray("NORMAL", TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, true, n, 4)
                        : makeArray("NORMAL", TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false, n, 12);
    PackedArray uv = q ? makeArray("TEXCOORD_0", TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, true, n, 4)
                       : makeArray("TEXCOORD_0", TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, false, n, 8);
    PackedArray col = makeArray("COLOR_0", TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC3, true,
                                f.colors ? n : 0, 4);
    const double inv_q = q ? 1.0 / f.quantum_m : 0.0;
    const int64_t tx = q ? std::llround(placed.translation[0] * inv_q) : 0;
    const int64_t tz = q ? std::llround(placed.translation[2] * inv_q) : 0;
    const float range = std::max(f.height_max - f.height_min, 1e-6f);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t v = chunk.vertices[i];
        const float* p = &mesh.positions[3 * v];
        const float* nn = &mesh.normals[3 * v];
        // Runtime frame (x east, y north, z up) to glTF (X east, Y up, Z south).
        const double col_px = p[0] / f.mpp_x, row_px = -p[1] / f.mpp_y;
        if (q) {
            const double east = tile.x0 * f.mpp_x + p[0], south = tile.y0 * f.mpp_y - p[1];
            const int64_t qv[3] = {roundToInt(east * inv_q) - tx, roundToInt(p[2] * inv_q) - f.y_offset_quanta,
                                   roundToInt(south * inv_q) - tz};
            double as_double[3];
            for (int c = 0; c < 3; ++c) {
                const uint16_t u = static_cast<uint16_t>(std::clamp<int64_t>(qv[c], 0, 65535));
                put(pos.bytes, i * 8 + 2 * c, u);
                as_double[c] = u;
            }
            trackMinMax(pos, as_double);
            const float gl_n[3] = {nn[0], nn[2], -nn[1]};
            quantizeNormal(gl_n, reinterpret_cast<int8_t*>(&nor.bytes[i * 4]));
            put(uv.bytes, i * 4, unorm16((tile.x0 + col_px) / (f.region_width - 1)));
            put(uv.bytes, i * 4 + 2, unorm16((tile.y0 + row_px) / (f.region_height - 1)));
        } else {
            const float gl_p[3] = {p[0], p[2], -p[1]};
            std::memcpy(&pos.bytes[i * 12], gl_p, 12);
            const double as_double[3] = {gl_p[0], gl_p[1], gl_p[2]};
            trackMinMax(pos, as_double);
            const float gl_n[3] = {nn[0], nn[2], -nn[1]};
            std::memcpy(&nor.bytes[i * 12], gl_n, 12);
            const float gl_uv[2] = {static_cast<float>((tile.x0 + col_px) / (f.region_width - 1)),
                                    static_cast<float>((tile.y0 + row_px) / (f.region_height - 1))};
            std::memcpy(&uv.bytes[i * 8], gl_uv, 8);
        }
        if (f.colors) {
            uint8_t type = 255;
            if (!tile.types.empty()) {
                const int cx = std::clamp(static_cast<int>(std::lround(col_px)), 0, tile.quads_x);
                const int cy = std::clamp(static_cast<int>(std::lround(row_px)), 0, tile.quads_y);
                type = tile.types[static_cast<size_t>(cy) * (tile.quads_x + 1) + cx];
            }
            const auto rgb = terrainColor((p[2] - f.height_min) / range, type);
            std::memcpy(&col.bytes[i * 4], rgb.data(), 3);
            col.bytes[i * 4 + 3] = 255;
        }
    }
    prim.attributes.push_back(std::move(pos));
    prim.attributes.push_back(std::move(nor));
    prim.attributes.push_back(std::move(uv));
    if (f.colors) prim.attributes.push_back(std::move(col));

    // 65535 is the primitive-restart value of 16-bit indices, so 16 bits hold up to 65535 vertices.
    const bool wide = n > 65535;
    prim.indices = makeArray("", wide ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                             TINYGLTF_TYPE_SCALAR, false, chunk.indices.size(), wide ? 4 : 2);
    prim.indices.byte_stride = 0;
    for (size_t k = 0; k < chunk.indices.size(); ++k) {
        if (wide) put(prim.indices.bytes, 4 * k, chunk.indices[k]);
        else put(prim.indices.bytes, 2 * k, static_cast<uint16_t>(chunk.indices[k]));
    }
    return prim;
}

}  // namespace

PackedTile packTile(const MeshedTile& tile, const PackingFrame& frame) {
    PackedTile packed;
    packed.tx = tile.tx, packed.ty = tile.ty;
    packed.size_m = std::max(tile.quads_x * frame.mpp_x, tile.quads_y * frame.mpp_y);
    const double east = tile.x0 * frame.mpp_x, south = tile.y0 * frame.mpp_y;
    if (frame.quantize) {
        // Whole quanta, so a vertex shared by two tiles dequantises to the same point in both.
        const double qm = frame.quantum_m;
        packed.translation[0] = std::llround(east / qm) * qm;
        packed.translation[1] = frame.y_offset_quanta * qm;
        packed.translation[2] = std::llround(south / qm) * qm;
        packed.scale = qm;
    } else {
        packed.translation[0] = east, packed.translation[2] = south;
    }
    const size_t limit = frame.quantize ? 65535 : std::numeric_limits<size_t>::max();
    for (const TileMesh& mesh : tile.lods) {
        std::vector<PackedPrimitive> prims;
        for (const Chunk& chunk : splitByVertexCount(mesh, limit)) prims.push_back(packChunk(tile, mesh, chunk, frame, packed));
        packed.lods.push_back(std::move(prims));
        packed.lod_errors_m.push_back(mesh.geometric_error_m);
    }
    return packed;
}

}  // namespace terrasynth::export_detail
