// Curve constraints (Gain et al. 2015 s5.1) rasterised into the correction kernel's blend sums.
#include "synth/curve_field.h"

#include "synth/curve_geometry.h"
#include "synth/curve_junctions.h"
#include "synth/curve_profile.h"
#include "synth/curve_raster.h"

namespace terrasynth::synth {

void accumulateCurves(const std::vector<CurveConstraint>& curves, int level, const LevelRegion& region,
                      double meters_per_pixel0, std::vector<float>& sums) {
    TERRASYNTH_REQUIRE(sums.size() == 3 * region.pixels(), "accumulateCurves: sums must hold 3 floats per region pixel");
    if (curves.empty()) return;
    // Courses are cached by their points (the distance field's geometry changes only when the
    // horizontal shape does); widgets and junction heights are cheap and rebuilt per call.
    std::vector<std::shared_ptr<const CourseSamples>> courses;
    std::vector<const CourseSamples*> raw;
    std::vector<CurveProfile> profiles;
    for (const CurveConstraint& curve : curves) {
        courses.push_back(cachedCourse(curve));
        raw.push_back(courses.back().get());
        profiles.emplace_back(curve.widgets, courses.back()->length);
    }
    pinJunctions(findCrossings(raw), profiles);
    for (size_t i = 0; i < curves.size(); ++i)
        accumulateCurve(*courses[i], profiles[i], level, region, meters_per_pixel0, true, sums);
}

}  // namespace terrasynth::synth
