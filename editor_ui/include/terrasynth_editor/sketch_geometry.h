// terrasynth_editor/sketch_geometry.h: the plane geometry of sketching tools, in level-0 pixels.
//
// Sketched strokes arrive as many close points; courses, lassos and ridges want fewer. Over-sketching
// (Gain et al. 2015 s3: a new stroke that starts and ends near an existing course replaces the part
// between those places), placing widgets by arc length, junctions between courses, lassos.
// Plain functions of their arguments, no UI.
#pragma once

#include <optional>
#include <utility>
#include <vector>

namespace terrasynth::editor {

using Polyline = std::vector<std::pair<double, double>>;

// Keeps the first and last point and every point at least `spacing` from the last kept one.
Polyline decimate(const Polyline& line, double spacing);
// Total length.
double polylineLength(const Polyline& line);
// The point at arc-length fraction t (0..1) of the polyline.
std::pair<double, double> pointAtFraction(const Polyline& line, double t);
// Nearest point of the polyline to p: its arc-length fraction (0..1), the distance, and the index of
// the segment it lies on (the segment from point i to point i + 1).
struct Nearest {
    double t = 0.0;
    double distance = 0.0;
    int segment = 0;
};
Nearest nearestOnPolyline(const Polyline& line, double x, double y);
// Over-sketch: `course` with its part between the points nearest to the stroke's ends replaced by
// the stroke (reversed first when drawn against the course's direction). When the stroke starts
// near an end of the course and runs past it, the course is extended instead.
Polyline overSketch(const Polyline& course, const Polyline& stroke);
// Points where two polylines cross (segment intersections), for showing junctions.
std::vector<std::pair<double, double>> crossings(const Polyline& a, const Polyline& b);
// Crossings of a polyline with itself (non-adjacent segments).
std::vector<std::pair<double, double>> selfCrossings(const Polyline& a);
// Area centroid of a closed polygon (the vertex mean when the area is ~0).
std::pair<double, double> centroid(const Polyline& polygon);
bool insidePolygon(const Polyline& polygon, double x, double y);

}  // namespace terrasynth::editor
