// Private: what the tools share (tools.cpp, tool_results.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include <osg/Vec2d>

#include "terrasynth/grid.h"
#include "terrasynth/layers_tools.h"

namespace terrasynth::editor::tools {

constexpr double kHandlePx = 12.0;          // how close (window pixels) the pointer must be to grab a handle
constexpr double kCourseSpacingPx = 6.0;    // level-0 pixels between kept course points
constexpr double kMinStrokeScreenPx = 6.0;  // shorter strokes are clicks

inline double screenDistance(const osg::Vec2d& a, const osg::Vec2d& b) { return (a - b).length(); }

// The region between two level-0 picks, in the layer stack's pixels (relative to the extent).
inline Region regionBetween(std::pair<double, double> a, std::pair<double, double> b, const PixelWindow& extent,
                            RegionShape shape) {
    Region r;
    r.shape = shape;
    r.x = std::min(a.first, b.first) - extent.x;
    r.y = std::min(a.second, b.second) - extent.y;
    r.width = std::fabs(a.first - b.first);
    r.height = std::fabs(a.second - b.second);
    return r;
}

}  // namespace terrasynth::editor::tools
