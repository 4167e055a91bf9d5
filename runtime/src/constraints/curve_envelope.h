// Private: the area-of-effect envelope of a curve constraint with isocurve smoothing (Gain et al.
// 2015 s5.1, Figure 5). Implemented in curve_envelope.cpp.
#pragma once

#include <cstdint>
#include <vector>

namespace terrasynth::constraints {

// One level's working grid around a curve: per pixel the envelope function f = (d - reach(t(p))) in
// level pixels (inside where f < 0; +infinity where the distance was not computed) and the arc length
// s of the pixel's closest course point (level-0 pixels; any value where f is infinite).
struct EnvelopeGrid {
    int x0 = 0, y0 = 0;  // global level pixel of grid pixel (0, 0)
    int width = 0, height = 0;
    std::vector<float> f;
    std::vector<double> s;
};

struct EnvelopeSmoothing {
    bool enabled = true;
    // Grid neighbours whose closest points are more than this far apart along the course (level-0
    // pixels) straddle a jump of the parametrisation (the medial axis on the concave side).
    double jump_arc_px = 8.0;
    // Contour vertices within `window` vertices of a jump are smoothed, with a weight falling
    // smoothly from 1 at the jump to 0 at the window's end; everything else keeps its exact position.
    int window = 8;
};

// Which grid pixels are inside the envelope (1) or not (0), row-major width x height.
// Without smoothing: f < 0. With smoothing (Figure 5b): the f = 0 isocurve is extracted by marching
// squares (the grid is closed with an outside ring so every contour is a loop), the stretches of the
// contour around parametrisation jumps are Laplacian-smoothed, and the smoothed loops are filled with
// the even-odd rule at pixel centres. Vertex positions are computed in global coordinates and depend
// only on nearby pixels, so overlapping grids agree wherever their contours are the same.
std::vector<uint8_t> envelopeMask(const EnvelopeGrid& grid, const EnvelopeSmoothing& smoothing);

// How far (in level pixels) the smoothing can move the contour's influence from where it starts:
// grids must extend this far beyond the pixels whose mask is used.
int envelopeInfluencePx(const EnvelopeSmoothing& smoothing);

}  // namespace terrasynth::constraints
