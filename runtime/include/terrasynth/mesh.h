// terrasynth/mesh.h: heightfield tiles to triangle meshes (plain data; no OSG, no GL).
//
// Coordinates: x east, y north, z up, metres, relative to the tile's north-west corner unless an
// origin is given. Renderers and exporters convert to their own frames (glTF: Y-up).
//
// Seams (docs/export.md): two tiles that share an edge share its samples (a tile of T quads has T+1
// samples per side), so at the same step their border vertices are identical. Simplification locks the
// border, so every simplified LOD keeps the full-resolution border and any mix of LODs is crack-free.
// Grid LODs (step > 1) either keep every border sample (`full_res_border`, stitched to the coarse
// interior, so any mix of LODs is crack-free with identical edge vertices) or only every step-th one
// (then finer neighbours leave T-junction gaps that skirts hide).
// Normals are central differences at the true spacing over +-step pixels (+-1 pixel on a full-resolution
// border, so edge normals match between LODs). Give the tile an apron (`border`) of at least that many
// pixels so neighbouring tiles compute identical normals on their shared edge (without one, edge
// normals are one-sided).
//
// Threading: meshHeightfield is a pure function; call it from any number of threads.
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
    uint32_t skirt_first_index = 0;   // indices from here on are skirt triangles (if any)
    // Largest vertical distance (metres) between a full-resolution sample of the meshed area and the
    // mesh surface above or below it: 0 at step 1 without simplification. What LOD selection and
    // tilesets call the geometric error.
    float geometric_error_m = 0.0f;

    size_t vertexCount() const { return positions.size() / 3; }
    size_t triangleCount() const { return indices.size() / 3; }
};

struct MeshOptions {
    // Grid step in heightfield pixels (1 = full resolution). The heightfield of a tile that is
    // meshed with step s should have (n*s + 1) samples per side so edges meet neighbours exactly.
    int step = 1;
    // Keep every border sample at any step, stitched to the coarse interior with fans: crack-free
    // between tiles of different steps without skirts. When the coarse grid would have fewer than 3
    // samples along an axis the step is reduced along it (a stitched cell needs an unstitched corner).
    bool full_res_border = false;
    // Apron in pixels on every side of `field` that is only read for normals (and the geometric
    // error), never meshed: the mesh covers [border, width-border) x [border, height-border).
    // 0 = mesh everything. 0 <= border, and at least one sample must remain.
    int border = 0;
    // Skirt depth in metres hanging below the tile border to hide cracks between LODs; 0 = none.
    float skirt_depth_m = 0.0f;
    // Target fraction of triangles to keep after simplification (meshoptimizer); 1 = no
    // simplification. Border vertices are locked so tiles stay crack-free. In (0, 1].
    // meshoptimizer's simplifier is not height-field aware: next to the locked border it leaves
    // vertical sliver triangles and, on steep ground, some triangles folded over in plan view. Prefer
    // step + full_res_border for terrain LODs; simplification suits irregular, error-bounded meshes.
    float simplify_ratio = 1.0f;
    // Upper bound (metres) on the error simplification may introduce; it stops early rather than
    // exceed it. 0 = no bound (the ratio alone decides).
    float simplify_max_error_m = 0.0f;
    // Reorder indices and vertices for the post-transform cache and fetch (meshoptimizer).
    bool optimize_order = true;
    // Offset added to x/y of every vertex (metres), e.g. the tile's world position.
    double origin_x_m = 0.0, origin_y_m = 0.0;
};

// Meshes the heightfield (less its `border`). `field` spacing gives the metres between samples.
// Vertices keep the grid's row-major order unless optimize_order is set or the mesh was simplified
// (then unused vertices are dropped and the rest follow first use). Skirt vertices and triangles come
// last. Preconditions (TERRASYNTH_REQUIRE): non-empty field, step >= 1, border >= 0 leaving at least
// 1 sample per side, 0 < simplify_ratio <= 1, skirt_depth_m >= 0.
TileMesh meshHeightfield(const Heightfield& field, const MeshOptions& options = {});

// Height of the grid mesh inside one cell, on the triangles meshHeightfield makes: corners nw, ne,
// sw, se (north-west ... south-east), split along the north-east to south-west diagonal into
// (nw, sw, ne) and (ne, sw, se). (fu, fw) in [0, 1]^2 is the position from the north-west corner,
// fu eastwards, fw southwards. Collision and picking use it so they meet the surface that is drawn.
inline double heightOnGridCell(double nw, double ne, double sw, double se, double fu, double fw) {
    if (fu + fw <= 1.0) return nw + fu * (ne - nw) + fw * (sw - nw);
    return se + (1.0 - fu) * (sw - se) + (1.0 - fw) * (ne - se);
}

// The grid step of LOD `lod` (0 = finest) when LODs halve the resolution: 2^lod.
inline int lodStep(int lod) { return 1 << lod; }
// The simplification ratio of LOD `lod` when LODs quarter the triangle count: 4^-lod.
inline float lodSimplifyRatio(int lod) { return 1.0f / static_cast<float>(1u << (2 * lod)); }

}  // namespace terrasynth
