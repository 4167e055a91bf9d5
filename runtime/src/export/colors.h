// Colours for exported terrain: a hypsometric tint over the height range, blended with a colour per
// terrain type; and an in-memory PNG encoder for the embedded texture.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth::export_detail {

// RGB for height `t` in [0, 1] of the range (lowland green to snow white), optionally blended half
// and half with the palette colour of `type` (255 = unknown: the tint alone).
std::array<uint8_t, 3> terrainColor(float t, uint8_t type);

// PNG bytes of an 8-bit RGB image (row-major, 3 bytes per pixel).
Result<std::string> encodePngRgb(int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace terrasynth::export_detail
