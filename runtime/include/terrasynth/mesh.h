// terrasynth/mesh.h: heightfield tiles to triangle meshes (plain data; no OSG, no GL).
//
// Coordinates: x east, y north, z up, metres, relative to the tile's north-west corner unless an
// origin is given. Renderers and exporters convert to their own frames (glTF: Y-up).
#pragma once

#include <cstdint>
#include <vector>

#include "terrasynth/heightfield.h"

namespace terrasynth {

struct TileMesh {
    std::vector<float> positions;  // xyz per vertex, metres
    std::vector<float> normals;    // unit xyz per vertex, from the heightfield's central differences
    std::vector<float> uvs;        // uv per vertex in [0,1] over the tile (u east, v south)
    std::vector<uint32_t> indices; // triangles, counter-clockwise seen from above
    uint32_t skirt_first_vertex = 0;  // vertices from here on belong to the skirt (if any)

    size_t vertexCount() const { return positions.size() / 3; }
    size_t triangleCount() const { return indices.size() / 3; }
};

struct MeshOptions {
    // Grid step in heightfield pixels (1 = full resolution). The heightfield of a tile that is
    // meshed with step s should have (n*s + 1) samples per side so edges meet neighbours exactly.
    int step = 1;
    // Skirt depth in metres hanging below the tile border to hide cracks between LODs; 0 = none.
    float skirt_depth_m = 0.0f;
    // Target fraction of triangles to keep after simplification (meshoptimizer); 1 = no
    // simplification. Border vertices are locked so tiles stay crack-free.
    float simplify_ratio = 1.0f;
    // Reorder indices and vertices for the post-transform cache and fetch (meshoptimizer).
    bool optimize_order = true;
    // Offset added to x/y of every vertex (metres), e.g. the tile's world position.
    double origin_x_m = 0.0, origin_y_m = 0.0;
};

// Meshes the whole heightfield. `field` spacing gives the metres between samples.
TileMesh meshHeightfield(const Heightfield& field, const MeshOptions& options = {});

}  // namespace terrasynth
