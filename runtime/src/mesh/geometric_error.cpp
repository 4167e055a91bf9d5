// Geometric error of a coarse or simplified tile: the largest vertical gap between the full-resolution
// heightfield and the mesh surface, found by rasterising every surface triangle over the pixel grid.
#include <algorithm>
#include <cmath>

#include "mesh/mesh_steps.h"

namespace terrasynth::mesh_detail {

float measureGeometricError(const Heightfield& field, const MeshOptions& options, const TileMesh& mesh) {
    const size_t surface_indices = mesh.skirt_first_index;  // skirts hang below the surface
    const double b = options.border;
    // Back from metres to (fractional) field pixels; vertices sit on whole pixels.
    auto pixel = [&](uint32_t v, double* gx, double* gy) {
        *gx = std::round((mesh.positions[3 * v] - options.origin_x_m) / field.meters_per_pixel_x + b);
        *gy = std::round((options.origin_y_m - mesh.positions[3 * v + 1]) / field.meters_per_pixel_y + b);
    };
    double worst = 0.0;
    for (size_t t = 0; t + 2 < surface_indices; t += 3) {
        double x[3], y[3], z[3];
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = mesh.indices[t + k];
            pixel(v, &x[k], &y[k]);
            z[k] = mesh.positions[3 * v + 2];
        }
        const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (std::fabs(area) < 1e-12) continue;
        const int x0 = static_cast<int>(std::min({x[0], x[1], x[2]})), x1 = static_cast<int>(std::max({x[0], x[1], x[2]}));
        const int y0 = static_cast<int>(std::min({y[0], y[1], y[2]})), y1 = static_cast<int>(std::max({y[0], y[1], y[2]}));
        for (int py = y0; py <= y1; ++py) {
            for (int px = x0; px <= x1; ++px) {
                // Barycentric weights; a small tolerance keeps samples on shared edges.
                const double w0 = ((x[1] - px) * (y[2] - py) - (x[2] - px) * (y[1] - py)) / area;
                const double w1 = ((x[2] - px) * (y[0] - py) - (x[0] - px) * (y[2] - py)) / area;
                const double w2 = 1.0 - w0 - w1;
                if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
                const double surface = w0 * z[0] + w1 * z[1] + w2 * z[2];
                worst = std::max(worst, std::fabs(field.at(px, py) - surface));
            }
        }
    }
    return static_cast<float>(worst);
}

}  // namespace terrasynth::mesh_detail
