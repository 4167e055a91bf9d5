// meshHeightfield: grid -> optional simplification -> cache/fetch order -> skirt -> geometric error.
#include <algorithm>

#include "mesh/mesh_steps.h"

namespace terrasynth {

using namespace mesh_detail;

TileMesh meshHeightfield(const Heightfield& field, const MeshOptions& options) {
    TERRASYNTH_REQUIRE(!field.empty() && field.heights.size() == field.size(), "meshHeightfield needs samples");
    TERRASYNTH_REQUIRE(options.step >= 1, "step must be at least 1");
    TERRASYNTH_REQUIRE(options.border >= 0 && 2 * options.border < field.width && 2 * options.border < field.height,
                       "border must leave at least one sample per side");
    TERRASYNTH_REQUIRE(options.simplify_ratio > 0.0f && options.simplify_ratio <= 1.0f,
                       "simplify_ratio must be in (0, 1]");
    TERRASYNTH_REQUIRE(options.skirt_depth_m >= 0.0f, "skirt_depth_m must not be negative");

    MeshOptions effective = options;
    // A stitched border cell is fanned from a corner away from the fine sides, so every axis needs at
    // least two cells.
    auto tooCoarse = [&](int step) {
        return gridSamples(field.width, options.border, step).size() < 3 ||
               gridSamples(field.height, options.border, step).size() < 3;
    };
    if (options.full_res_border)
        while (effective.step > 1 && tooCoarse(effective.step)) effective.step = std::max(1, effective.step / 2);
    const std::vector<int> cols = gridSamples(field.width, options.border, effective.step);
    const std::vector<int> rows = gridSamples(field.height, options.border, effective.step);
    std::vector<uint32_t> ring;
    TileMesh mesh = buildGrid(field, effective, cols, rows, &ring);
    if (mesh.indices.empty()) {  // a single row or column has no surface
        mesh.skirt_first_vertex = static_cast<uint32_t>(mesh.vertexCount());
        return mesh;
    }

    const bool simplified = options.simplify_ratio < 1.0f &&
                            simplifyLockedBorder(mesh, options.simplify_ratio, options.simplify_max_error_m);
    // The grid is emitted in cache order already; only simplification scrambles it.
    if (options.optimize_order || simplified) optimizeAndCompact(mesh, ring, options.optimize_order && simplified);
    mesh.skirt_first_vertex = static_cast<uint32_t>(mesh.vertexCount());
    mesh.skirt_first_index = static_cast<uint32_t>(mesh.indices.size());
    if (options.skirt_depth_m > 0.0f) appendSkirt(mesh, ring, /*closed=*/true, options.skirt_depth_m);
    if (effective.step > 1 || simplified) mesh.geometric_error_m = measureGeometricError(field, options, mesh);
    return mesh;
}

}  // namespace terrasynth
