// D8 flow routing on the Priority-Flood+epsilon filled surface, exposing the filled surface too so
// computeTerrainStats gets drainage area and depression share from one fill.
#pragma once

#include <vector>

#include "terrasynth/heightfield.h"

namespace terrasynth::stats {

struct FlowRouting {
    std::vector<double> filled;  // Priority-Flood+epsilon in double precision
    std::vector<double> area;    // drainage area, m^2
};

FlowRouting routeFlow(const Heightfield& field);

// Whether a cell was raised by more than the epsilon steps across flats, i.e. lies in a depression.
// Epsilon steps in double are ~1e-13 m, while filling a depression raises a float height by at least
// one float step (>= 1e-7 of its magnitude), so half a float step separates the two.
bool inDepression(float original, double filled);

}  // namespace terrasynth::stats
