// Six landform classes from slope, profile and plan curvature (docs/realism.md, "Landform classes").
// The scheme follows Pennock, Zebarth & de Jong (1987): level ground first, then curvature decides;
// here plan curvature separates divergent crests from convergent channels before profile curvature
// separates shoulders, footslopes and planar backslopes.
#include <cmath>

#include "stats/field_check.h"
#include "stats/window3x3.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {

const char* landformName(Landform landform) {
    switch (landform) {
        case Landform::Flat: return "flat";
        case Landform::PeakRidge: return "peak/ridge";
        case Landform::ValleyChannel: return "valley/channel";
        case Landform::Shoulder: return "shoulder";
        case Landform::Footslope: return "footslope";
        case Landform::Backslope: return "backslope";
    }
    return "?";
}

std::vector<uint8_t> classifyLandforms(const Heightfield& field, const LandformThresholds& thresholds) {
    stats::requireField(field);
    const double flat_gradient = std::tan(thresholds.flat_slope_deg * 3.14159265358979323846 / 180.0);
    // At least the gradient that gives curvature a direction.
    const double min_gradient = std::max(flat_gradient, stats::kMinGradientForDirection);
    const double t = thresholds.curvature_gradient_change /
                     std::sqrt(field.meters_per_pixel_x * field.meters_per_pixel_y);
    std::vector<uint8_t> classes(field.size());
    for (int y = 0; y < field.height; ++y)
        for (int x = 0; x < field.width; ++x) {
            const stats::Derivatives d = stats::derivativesAt(field, x, y);
            Landform c;
            if (std::sqrt(d.zx * d.zx + d.zy * d.zy) < min_gradient) {
                c = Landform::Flat;
            } else {
                double profile, plan;
                stats::convexities(d, &profile, &plan);
                if (plan > t && profile >= -t) c = Landform::PeakRidge;
                else if (plan < -t && profile <= t) c = Landform::ValleyChannel;
                else if (profile > t) c = Landform::Shoulder;
                else if (profile < -t) c = Landform::Footslope;
                else c = Landform::Backslope;
            }
            classes[static_cast<size_t>(y) * field.width + x] = static_cast<uint8_t>(c);
        }
    return classes;
}

}  // namespace terrasynth
