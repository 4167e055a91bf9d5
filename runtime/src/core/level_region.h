// Private: a rectangle of one pyramid level in that level's global pixel coordinates (a level-i pixel
// covers 2^i x 2^i level-0 pixels), the unit in which synthesis plans its work and constraints are
// rasterised.
#pragma once

#include <cstddef>

namespace terrasynth::core {

struct LevelRegion {
    int x = 0, y = 0;          // global pixel of the region's north-west corner at this level
    int width = 0, height = 0;
    size_t pixels() const { return static_cast<size_t>(width) * height; }
};

}  // namespace terrasynth::core
