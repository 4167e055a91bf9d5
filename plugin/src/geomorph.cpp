// Geomorphing data: where each vertex of a tile would be on its parent's surface. The vertex shader
// (terrain_shader.cpp) blends towards it as the tile nears the distance at which the parent takes
// over, so LOD switches do not pop.
#include <cmath>
#include <limits>

#include <osg/Geometry>
#include <osg/MatrixTransform>

#include "terrasynth_plugin/tile_builder.h"

namespace terrasynth::plugin {

std::vector<float> parentSurfaceHeights(const TileMesh& mesh, const Heightfield& parent, double spacing, int step,
                                        float skirt_depth_m) {
    // Parent vertices sit on every other vertex of ours; parent vertex q is parent sample q * step.
    auto p = [&](int64_t qx, int64_t qy) { return parent.at(static_cast<int>(qx * step), static_cast<int>(qy * step)); };
    std::vector<float> out(mesh.vertexCount());
    for (size_t v = 0; v < out.size(); ++v) {
        const int64_t col = std::llround(mesh.positions[3 * v] / spacing);
        const int64_t row = std::llround(-mesh.positions[3 * v + 1] / spacing);
        const int64_t u = col / step, w = row / step;  // our vertex indices
        float h;
        if (u % 2 == 0 && w % 2 == 0) {
            h = p(u / 2, w / 2);
        } else if (w % 2 == 0) {
            h = 0.5f * (p((u - 1) / 2, w / 2) + p((u + 1) / 2, w / 2));
        } else if (u % 2 == 0) {
            h = 0.5f * (p(u / 2, (w - 1) / 2) + p(u / 2, (w + 1) / 2));
        } else {
            // Cell centre: on the parent's diagonal from its north-east to its south-west corner
            // (the triangulation of terrasynth/mesh.h grids).
            const int64_t u0 = (u - 1) / 2, w0 = (w - 1) / 2;
            h = 0.5f * (p(u0 + 1, w0) + p(u0, w0 + 1));
        }
        out[v] = v >= mesh.skirt_first_vertex && mesh.skirt_first_vertex > 0 ? h - skirt_depth_m : h;
    }
    return out;
}

Heightfield parentSamplesFromNode(const osg::Node& parent_node, const TileKey& child, const TileBuildSettings& s) {
    const osg::Vec3Array* vertices = tileVertices(parent_node);
    if (!vertices) return {};
    const int half = s.layout.tile_size / 2;
    const double spacing = s.layout.spacing(child.level + 1);
    const int64_t x0 = (child.x - 2 * child.parent().x) * half, y0 = (child.y - 2 * child.parent().y) * half;
    Heightfield out(half + 1, half + 1, spacing, std::numeric_limits<float>::lowest());
    // Skirt vertices repeat a border vertex lower down: the top surface is the highest per sample.
    for (const osg::Vec3f& v : *vertices) {
        const int64_t col = std::llround(v.x() / spacing) - x0, row = std::llround(-v.y() / spacing) - y0;
        if (col < 0 || row < 0 || col > half || row > half) continue;
        float& h = out.at(static_cast<int>(col), static_cast<int>(row));
        h = std::max(h, v.z());
    }
    for (int row = 0; row <= half; row += s.mesh_step)
        for (int col = 0; col <= half; col += s.mesh_step)
            if (out.at(col, row) == std::numeric_limits<float>::lowest()) return {};  // not our layout
    return out;
}

}  // namespace terrasynth::plugin
