// Private: painted type and freeze masks (TypePaint) read on other pixel rectangles. Painting itself
// is public (paintStroke, terrasynth/constraints.h) and implemented in type_paint.cpp.
#pragma once

#include <cstdint>
#include <vector>

#include "terrasynth/constraints.h"
#include "terrasynth/grid.h"

namespace terrasynth::constraints {

// `paint` on the pixels of `window` (nearest; pixels outside the paint read `outside`).
std::vector<uint8_t> paintOnWindow(const TypePaint& paint, const PixelWindow& window, uint8_t outside);

}  // namespace terrasynth::constraints
