// Private: parseConstraints on parsed JSON, with masks from anywhere (files, or memory when a saved
// session's reference constraints come back from its sidecar).
#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "terrasynth/constraints.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth::project {

// The 8-bit mask a constraints object names (its "mask" string, as written); errors name the mask.
using MaskReader = std::function<Result<Image8>(const std::string& name)>;
// Masks as files relative to base_dir (what parseConstraints uses).
MaskReader masksFromFolder(const std::string& base_dir);
// Masks from a constraintsToJson result, by the name its JSON gives them.
MaskReader masksFrom(const ConstraintsJson& written);

Result<SynthesisConstraints> parseConstraintsJson(const nlohmann::json& constraints, const MaskReader& masks,
                                                  const ExemplarDatabase& db, int64_t extent_x, int64_t extent_y,
                                                  int extent_width, int extent_height);

}  // namespace terrasynth::project
