// Private: junctions of curve constraints (Gain et al. 2015 s3: "At curve intersections (including
// self-intersections) we automatically place junction-located widgets ... controlling only height").
// Implemented in curve_junctions.cpp.
#pragma once

#include <cstddef>
#include <vector>

#include "constraints/curve_geometry.h"
#include "constraints/curve_profile.h"
#include "terrasynth/limits.h"

namespace terrasynth::constraints {

// A crossing of course a at arc length s_a with course b at s_b (a == b for a self-intersection).
struct CourseCrossing {
    size_t a = 0, b = 0;
    double s_a = 0.0, s_b = 0.0;
    double x = 0.0, y = 0.0;  // level-0 global pixels
};

// Every crossing between the courses and of each course with itself (segments sharing a sample are
// not crossings). Crossings closer than 1 pixel along both courses are reported once. Uses a
// uniform grid of segments, so the cost is about linear in the total course length, unless courses
// pile up in a few grid cells (a scribble): then the search stops once it would test more than
// kMaxCrossingTests segment pairs or find more than limits::kMaxJunctions crossings, and says so.
struct CrossingSearch {
    std::vector<CourseCrossing> crossings;
    bool complete = true;  // false: a limit was reached, `crossings` holds what was found before
};
constexpr uint64_t kMaxCrossingTests = 50000000;
CrossingSearch findCrossings(const std::vector<const CourseSamples*>& courses);

// A widget within this arc length of a crossing specifies the junction's height.
constexpr double kJunctionWidgetSnapPx = 2.0;

// Pins every crossing's height on both profiles: the junction height is the height of the widget(s)
// sitting at the crossing if any, else the mean of the crossing courses' widget heights there. The
// correction blends in over the larger of the two curves' reaches at the crossing (at least 4 px).
void pinJunctions(const std::vector<CourseCrossing>& crossings, std::vector<CurveProfile>& profiles);

}  // namespace terrasynth::constraints
