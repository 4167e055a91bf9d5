// Private: parseConstraints on parsed JSON, with masks from anywhere (files, or memory when a saved
// session's reference constraints come back from its sidecar).
#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "terrasynth/constraints.h"
#include "terrasynth/grid.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth::synth {

// The 8-bit mask a constraints object names (its "mask" string, as written); errors name the mask.
using MaskReader = std::function<Result<Image8>(const std::string& name)>;
// Masks as files relative to base_dir (what parseConstraints uses).
MaskReader masksFromFolder(const std::string& base_dir);
// Masks from a constraintsToJson result, by the name its JSON gives them.
MaskReader masksFrom(const ConstraintsJson& written);

// `paint` on the pixels of `window` (nearest; pixels outside the paint read `outside`).
std::vector<uint8_t> paintOnWindow(const TypePaint& paint, const PixelWindow& window, uint8_t outside);

Result<SynthesisConstraints> parseConstraintsJson(const nlohmann::json& constraints, const MaskReader& masks,
                                                  const ExemplarDatabase& db, int64_t extent_x, int64_t extent_y,
                                                  int extent_width, int extent_height);

}  // namespace terrasynth::synth
