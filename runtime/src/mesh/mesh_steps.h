// Private steps of meshHeightfield (runtime/src/mesh); each lives in its own file.
#pragma once

#include <cstdint>
#include <vector>

#include "terrasynth/mesh.h"

namespace terrasynth::mesh_detail {

// The field columns (or rows) a grid of `step` samples along an axis of `size` samples with an apron of
// `border` keeps: border, border+step, ... and always the last inner sample, so the far edge is exact
// even when (inner size - 1) is not a multiple of step.
std::vector<int> gridSamples(int size, int border, int step);

// A regular grid over the sampled columns x rows (vertex (i, j) at index j*cols.size()+i), followed by
// the fine border samples when options.full_res_border is set; positions, normals, uvs and
// counter-clockwise triangles, already in a vertex-cache-friendly order. `ring` receives every border vertex, clockwise seen from above from the
// north-west corner (empty when the grid has a single row or column).
TileMesh buildGrid(const Heightfield& field, const MeshOptions& options, const std::vector<int>& cols,
                   const std::vector<int>& rows, std::vector<uint32_t>* ring);

// Simplifies `mesh.indices` towards ratio * triangle count with the border locked (meshoptimizer).
// Returns false (mesh untouched) when meshoptimizer is not available.
bool simplifyLockedBorder(TileMesh& mesh, float ratio, float max_error_m);

// Reorders triangles for the post-transform cache (meshoptimizer) when `cache`, then vertices in
// first-use order for fetch locality, dropping unused ones. `ring` (vertex indices) is remapped to the
// new numbering.
void optimizeAndCompact(TileMesh& mesh, std::vector<uint32_t>& ring, bool cache);

// Appends a skirt: one vertex `depth_m` below each ring vertex (same normal and uv) and two
// outward-facing triangles per ring edge. `closed` joins the last ring vertex to the first.
void appendSkirt(TileMesh& mesh, const std::vector<uint32_t>& ring, bool closed, float depth_m);

// Largest |height - mesh surface| over the full-resolution samples the surface triangles cover.
float measureGeometricError(const Heightfield& field, const MeshOptions& options, const TileMesh& mesh);

}  // namespace terrasynth::mesh_detail
