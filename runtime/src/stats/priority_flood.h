// Priority-Flood depression filling on a raw grid (Barnes, Lehman & Mulla 2014), for float heights
// (the public fillDepressions) and double heights (flow routing, where one epsilon step is ~1e-13 m
// so filled flats stay flat to any practical precision).
#pragma once

#include <vector>

namespace terrasynth::stats {

// Fills `z` (width*height, row-major) in place. epsilon: see fillDepressions in terrain_stats.h.
template <class T>
void priorityFlood(std::vector<T>& z, int width, int height, bool epsilon);

extern template void priorityFlood<float>(std::vector<float>&, int, int, bool);
extern template void priorityFlood<double>(std::vector<double>&, int, int, bool);

}  // namespace terrasynth::stats
