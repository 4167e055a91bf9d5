// Simplification with a locked border and cache/fetch ordering, both through meshoptimizer.
#include <algorithm>
#include <cfloat>

#include "mesh/mesh_steps.h"

#if __has_include(<meshoptimizer.h>)
#include <meshoptimizer.h>
#define TERRASYNTH_HAVE_MESHOPT 1
#endif

namespace terrasynth::mesh_detail {

bool simplifyLockedBorder(TileMesh& mesh, float ratio, float max_error_m) {
#ifdef TERRASYNTH_HAVE_MESHOPT
    const size_t vertex_count = mesh.vertexCount();
    const size_t target = std::max<size_t>(3, static_cast<size_t>(mesh.triangleCount() * ratio) * 3);
    // meshoptimizer measures error relative to the mesh extent; convert the bound in metres.
    const float scale = meshopt_simplifyScale(mesh.positions.data(), vertex_count, 3 * sizeof(float));
    const float target_error = max_error_m > 0.0f && scale > 0.0f ? max_error_m / scale : FLT_MAX;
    std::vector<uint32_t> simplified(mesh.indices.size());
    const size_t count =
        meshopt_simplify(simplified.data(), mesh.indices.data(), mesh.indices.size(), mesh.positions.data(),
                         vertex_count, 3 * sizeof(float), target, target_error, meshopt_SimplifyLockBorder, nullptr);
    simplified.resize(count);
    mesh.indices = std::move(simplified);
    return true;
#else
    (void)mesh, (void)ratio, (void)max_error_m;
    return false;
#endif
}

namespace {

template <size_t N>
void remapStream(std::vector<float>& stream, const std::vector<uint32_t>& remap, size_t new_count) {
    std::vector<float> out(new_count * N);
    for (size_t v = 0; v < remap.size(); ++v)
        if (remap[v] != ~0u) std::copy_n(&stream[v * N], N, &out[remap[v] * N]);
    stream = std::move(out);
}

}  // namespace

void optimizeAndCompact(TileMesh& mesh, std::vector<uint32_t>& ring, bool cache) {
    const size_t vertex_count = mesh.vertexCount();
#ifdef TERRASYNTH_HAVE_MESHOPT
    if (cache) {
        std::vector<uint32_t> ordered(mesh.indices.size());
        meshopt_optimizeVertexCache(ordered.data(), mesh.indices.data(), mesh.indices.size(), vertex_count);
        mesh.indices = std::move(ordered);
    }
#else
    (void)cache;
#endif
    // First-use order: what meshopt_optimizeVertexFetchRemap computes, in one pass.
    std::vector<uint32_t> remap(vertex_count, ~0u);
    size_t used = 0;
    for (uint32_t index : mesh.indices)
        if (remap[index] == ~0u) remap[index] = static_cast<uint32_t>(used++);
    // The border ring must survive: simplification locks it and it always bounds some triangle.
    for (uint32_t& v : ring) {
        TERRASYNTH_REQUIRE(remap[v] != ~0u, "a border vertex lost all its triangles");
        v = remap[v];
    }
    for (uint32_t& index : mesh.indices) index = remap[index];
    remapStream<3>(mesh.positions, remap, used);
    remapStream<3>(mesh.normals, remap, used);
    remapStream<2>(mesh.uvs, remap, used);
}

}  // namespace terrasynth::mesh_detail
