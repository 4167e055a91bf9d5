// Curve constraints (Gain et al. 2015 s5.1) rasterised into the correction kernel's blend sums.
#include "synth/curve_field.h"

#include "synth/curve_junctions.h"
#include "synth/curve_raster.h"

namespace terrasynth::synth {

PinnedCurves pinCurves(const std::vector<CurveConstraint>& curves) {
    // Courses are cached by their points (the distance field's geometry changes only when the
    // horizontal shape does); widgets and junction heights are cheap and rebuilt per call.
    PinnedCurves pinned;
    std::vector<const CourseSamples*> raw;
    for (const CurveConstraint& curve : curves) {
        pinned.courses.push_back(cachedCourse(curve));
        raw.push_back(pinned.courses.back().get());
        pinned.profiles.emplace_back(curve.widgets, pinned.courses.back()->length);
        pinned.profiles.back().setLift(curve.lift_m);
    }
    pinJunctions(findCrossings(raw), pinned.profiles);
    return pinned;
}

void accumulateCurves(const std::vector<CurveConstraint>& curves, int level, const LevelRegion& region,
                      double meters_per_pixel0, std::vector<float>& sums, bool held_free_level) {
    TERRASYNTH_REQUIRE(sums.size() == 3 * region.pixels(), "accumulateCurves: sums must hold 3 floats per region pixel");
    if (curves.empty()) return;
    const PinnedCurves pinned = pinCurves(curves);
    for (size_t i = 0; i < curves.size(); ++i)
        accumulateCurve(*pinned.courses[i], pinned.profiles[i], level, region, meters_per_pixel0, true, sums,
                        held_free_level);
}

}  // namespace terrasynth::synth
