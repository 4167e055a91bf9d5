// Slope and curvature maps from 3x3 central differences (Zevenbergen & Thorne 1987).
#include <cmath>
#include <limits>

#include "stats/field_check.h"
#include "stats/window3x3.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {

using stats::requireField;

std::vector<float> slopeDegrees(const Heightfield& field) {
    requireField(field);
    constexpr double kDegrees = 180.0 / 3.14159265358979323846;
    std::vector<float> slope(field.size());
    for (int y = 0; y < field.height; ++y)
        for (int x = 0; x < field.width; ++x) {
            const stats::Derivatives d = stats::derivativesAt(field, x, y);
            slope[static_cast<size_t>(y) * field.width + x] =
                static_cast<float>(std::atan(std::sqrt(d.zx * d.zx + d.zy * d.zy)) * kDegrees);
        }
    return slope;
}

CurvatureMaps curvatures(const Heightfield& field) {
    requireField(field);
    CurvatureMaps maps;
    maps.profile.assign(field.size(), std::numeric_limits<float>::quiet_NaN());
    maps.plan.assign(field.size(), std::numeric_limits<float>::quiet_NaN());
    constexpr double kMinP = stats::kMinGradientForDirection * stats::kMinGradientForDirection;
    for (int y = 0; y < field.height; ++y)
        for (int x = 0; x < field.width; ++x) {
            const stats::Derivatives d = stats::derivativesAt(field, x, y);
            if (d.zx * d.zx + d.zy * d.zy < kMinP) continue;
            double profile, plan;
            stats::convexities(d, &profile, &plan);
            const size_t i = static_cast<size_t>(y) * field.width + x;
            maps.profile[i] = static_cast<float>(profile);
            maps.plan[i] = static_cast<float>(plan);
        }
    return maps;
}

}  // namespace terrasynth
