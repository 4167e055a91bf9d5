// Private: curve constraints (Gain et al. 2015 s5.1) rasterised into the per-pixel blend sums the
// correction kernel consumes. Implemented in curve_field.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "constraints/curve_geometry.h"
#include "constraints/curve_profile.h"
#include "core/level_region.h"
#include "terrasynth/constraints.h"

namespace terrasynth::constraints {

// The courses of a set of curves and their properties along them with the junctions pinned and the
// lifts set: what accumulateCurves rasterises, and what the finished course is measured against.
struct PinnedCurves {
    std::vector<std::shared_ptr<const CourseSamples>> courses;  // cached by course (s5.1)
    std::vector<CurveProfile> profiles;
};
PinnedCurves pinCurves(const std::vector<CurveConstraint>& curves);

// Adds every curve's contribution at `level` to `sums`, 3 floats per pixel of `region` (row-major):
// sum of b, sum of b * h_t (metres), sum of b * d (level-0 pixels), with b = 1 / max(d, 0.5) the
// inverse-distance blend weight of s5.1 ("we maintain the sums ..."), d the distance of the pixel
// centre (level-0 pixel coordinates of a level-i pixel p: (p + 0.5) * 2^i - 0.5) to the closest point
// of the course, and h_t = height(t) + lift(t) + gradient_side(t) * d * meters_per_pixel0 at that
// closest point. A pixel is affected only within the side's reach at t, localised per level to
// min(reach, kPointLocalisation * 2^level) as for points. `sums` must have 3 * region.pixels() floats.
// `held_free_level`: see accumulateCurve (curve_raster.h).
void accumulateCurves(const std::vector<CurveConstraint>& curves, int level, const core::LevelRegion& region,
                      double meters_per_pixel0, std::vector<float>& sums, bool held_free_level = false);

// The cost limits of curve constraints (limits.h): counts, coordinates within
// +-limits::kMaxWindowOrigin, the total course length and the junction count. Cheap checks first;
// the junctions are found on the cached samplings accumulateCurves uses. `where` prefixes messages
// ("constraints.curves").
Status checkCurveLimits(const std::vector<CurveConstraint>& curves, const std::string& where);

}  // namespace terrasynth::constraints
