// terrasynth/curve_course.h: where a curve constraint's course runs and what it asks for along it
// (Gain et al. 2015 s3, s5.1), for editors that draw curves and for measuring how well a synthesis
// holds them. The values are exactly those the correction kernels are fed (docs/curves.md).
//
// Threading: re-entrant (the course cache behind it is thread-safe).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "terrasynth/constraints.h"
#include "terrasynth/heightfield.h"

namespace terrasynth {

struct CurveCourseSample {
    double x = 0.0, y = 0.0;          // level-0 global pixels
    double s = 0.0;                   // arc length from the start, level-0 pixels
    double t = 0.0;                   // s / course length, 0..1
    double left_x = 0.0, left_y = 0.0;  // unit normal towards the curve's left (x east, y south)
    // The widgets' height with the junctions pinned: what the finished course should hold, metres.
    float height_m = 0.0f;
    float left_gradient = 0.0f, right_gradient = 0.0f;  // rise per metre away from the course
    float left_reach_px = 0.0f, right_reach_px = 0.0f;  // level-0 pixels
    float lift_m = 0.0f;              // the curve's lift profile at s (CurveConstraint::lift_m)
};

// Samples curve `index` of `curves` every `step_px` (> 0) level-0 pixels of arc length, both ends
// included; junctions are found among all of `curves` (they pin the heights of the courses that
// cross). Empty when the course has fewer than two distinct points. Precondition: index < size.
std::vector<CurveCourseSample> sampleCurveCourse(const std::vector<CurveConstraint>& curves, size_t index,
                                                 double step_px = 1.0);

// How closely finished heights hold curve `index` of `curves` (the junctions among all of them):
// per course sample (every level-0 pixel of arc length) the finished height (bilinear at the
// sample) minus the asked height, and per sample and side with a reach of at least 4 px the
// gradient measured from the course to half the reach along the normal minus the asked gradient
// (metres per metre). `heights` is a level-0 field whose pixel (0, 0) is global pixel (origin_x,
// origin_y), spacing meters_per_pixel (> 0); samples it does not hold are skipped.
struct CurveHold {
    std::vector<float> height_error_m;
    std::vector<float> gradient_error;
};
CurveHold measureCurveHold(const Heightfield& heights, int64_t origin_x, int64_t origin_y,
                           const std::vector<CurveConstraint>& curves, size_t index, double meters_per_pixel);

}  // namespace terrasynth
