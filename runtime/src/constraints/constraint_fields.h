// Private: what the correction kernels need of the user's constraints at one level and region
// (Gain et al. 2015 s5.1-5.2), computed on the host and shared by both backends.
#pragma once

#include <cstdint>
#include <vector>

#include "core/level_region.h"
#include "terrasynth/constraints.h"

namespace terrasynth::constraints {

struct LevelConstraints {
    // Per region pixel, 4 floats: the inverse-distance blend sums of s5.1 over every point and curve
    // constraint reaching it (sum b, sum b*h_t in metres, sum b*d in level-0 pixels, 0). Keeping
    // sums means one constraint can be subtracted, changed and added back without re-evaluating the
    // others. Empty when no constraint reaches the region, and on the finest two levels unless
    // they hold the constraints' own pixels (constraintsForLevel).
    std::vector<float> blend;
    // One mask per region pixel (bit t = type t allowed; 0 = any type). Empty when nothing painted
    // reaches the region. R^i is the union of the painted level-0 types under the pixel's 2^i x 2^i
    // block, which equals the paper's recursive union that skips the all-types set (unpainted
    // pixels add nothing).
    std::vector<uint32_t> target_sets;
    // On the finest two levels (below first_constrained_level) the paper turns type constraints off
    // (s5.2, last paragraph). They only keep there: a pixel whose source is of a painted type takes
    // no candidate of another type, one whose source is not is free, and nothing is seeded. Free,
    // those levels' candidates carried other types into small painted regions: a 30 px disc kept
    // 92.2% of its type (ConstraintsCli.PaintedPixelsDrawFromThePaintedTypeInTheSourcesMap) once
    // the offset relaxation changed what the finest levels' candidates match.
    bool types_keep_only = false;
};

// Below `first_level` (SynthesisParams::first_constrained_level) the painted types kept only
// (types_keep_only) and no blend, or with `hold_free_levels` (SynthesisParams::hold_on_free_levels)
// the constraints' own pixels: the points' 7x7 sites, and the curves within the usual localisation
// but held softly (accumulateCurve, curve_raster.h).
// From `first_level` up, a point acts over its whole radius (accumulatePoint) and a curve over its
// reach localised to min(reach, kPointLocalisation * 2^level).
LevelConstraints constraintsForLevel(const SynthesisConstraints* constraints, int level, int first_level,
                                     bool hold_free_levels, const core::LevelRegion& region, double meters_per_pixel0);

// The target sets R^i of `paint` on `region` of `level` (LevelConstraints::target_sets) on any level,
// the free ones included; empty when nothing painted reaches the region.
std::vector<uint32_t> paintedTargetSets(const TypePaint& paint, int level, const core::LevelRegion& region);

// Half the width of a point's own 7x7 pixels (level-0 pixels from the site): held on the free levels
// so the slope seen over them holds.
constexpr double kSiteHalfWidthPx = 3.5;

// Adds (sign +1) or removes (-1) one point constraint's terms to/from 4-float blend sums of `region`,
// over its whole radius, or with `localisation_px` > 0 over min(radius, localisation_px).
void accumulatePoint(const PointConstraint& point, int level, const core::LevelRegion& region, double meters_per_pixel0,
                     float sign, std::vector<float>& blend, double localisation_px = 0.0);

}  // namespace terrasynth::constraints
