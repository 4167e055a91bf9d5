// Geomorphing data: where each vertex of a tile would be on its parent's surface. The vertex shader
// (terrain_shader.cpp) blends towards it as the tile nears the distance at which the parent takes
// over, so LOD switches do not pop.
#include <cmath>

#include "tile_builder.h"

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

}  // namespace terrasynth::plugin
