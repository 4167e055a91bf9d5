// Skirts: a curtain hanging below the tile border that hides T-junction gaps where a tile meets a
// neighbour of another grid LOD.
#include "mesh/mesh_steps.h"

namespace terrasynth::mesh_detail {

void appendSkirt(TileMesh& mesh, const std::vector<uint32_t>& ring, bool closed, float depth_m) {
    const uint32_t first = static_cast<uint32_t>(mesh.vertexCount());
    mesh.skirt_first_vertex = first;
    mesh.skirt_first_index = static_cast<uint32_t>(mesh.indices.size());
    for (uint32_t v : ring) {
        mesh.positions.insert(mesh.positions.end(),
                              {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2] - depth_m});
        // The border's own normal and uv, so lighting and texture run on smoothly down the curtain.
        mesh.normals.insert(mesh.normals.end(), {mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]});
        mesh.uvs.insert(mesh.uvs.end(), {mesh.uvs[2 * v], mesh.uvs[2 * v + 1]});
    }
    const size_t n = ring.size();
    const size_t edges = closed ? n : n - 1;
    for (size_t k = 0; k < edges; ++k) {
        const size_t k1 = (k + 1) % n;
        const uint32_t top0 = ring[k], top1 = ring[k1];
        const uint32_t low0 = first + static_cast<uint32_t>(k), low1 = first + static_cast<uint32_t>(k1);
        // The ring runs clockwise seen from above, so (top0, top1, low0) faces outwards.
        mesh.indices.insert(mesh.indices.end(), {top0, top1, low0, top1, low1, low0});
    }
}

}  // namespace terrasynth::mesh_detail
