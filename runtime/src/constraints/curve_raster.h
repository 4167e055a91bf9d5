// Private: one curve constraint rasterised into the blend sums of one level (Gain et al. 2015 s5.1).
// accumulateCurves (curve_field.h) prepares the courses and junctions and calls this per curve.
// Implemented in curve_raster.cpp.
#pragma once

#include <vector>

#include "constraints/curve_envelope.h"
#include "constraints/curve_geometry.h"
#include "constraints/curve_profile.h"
#include "core/level_region.h"

namespace terrasynth::constraints {

// Smoothing parameters used for a level: jumps are arc-length differences of more than 3 level
// pixels between grid neighbours; the smoothing window spans the localised envelope width.
EnvelopeSmoothing envelopeSmoothingForLevel(int level, double max_reach_px);

// Adds the curve's (b, b*h_t, b*d) to `sums` (3 floats per pixel of `region`), see curve_field.h.
// `smooth` = false keeps the raw envelope d < reach(t(p)) of Figure 5a (for comparison in tests).
// `held_free_level`: the level is one of the free finest levels and the course is held there
// softly (SynthesisParams::hold_on_free_levels): the sides meet in a rounded floor kHeldFloorCells
// level pixels wide instead of a crease, and phi_d's tolerance is widened by kHeldCourseToleranceM
// (through the blend's distance term), so the free levels keep their own detail and only what
// strays beyond it is pulled back.
void accumulateCurve(const CourseSamples& course, const CurveProfile& profile, int level, const core::LevelRegion& region,
                     double meters_per_pixel0, bool smooth, std::vector<float>& sums, bool held_free_level = false);

constexpr double kHeldFloorCells = 2.0;
constexpr double kHeldCourseToleranceM = 80.0;

}  // namespace terrasynth::constraints
