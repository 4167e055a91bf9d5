// Private: JSON sidecar helpers shared by the exemplar readers and heightfield writers.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/json_reader.h"
#include "core/paths.h"
#include "terrasynth/status.h"

namespace terrasynth::detail {

Result<nlohmann::json> readJsonFile(const std::string& path);

// Reads a number field; error names the file and the key.
Result<double> requireNumber(const nlohmann::json& j, const char* key, const std::string& file);
// Reads meters_per_pixel given as a number or [x, y].
Status readSpacing(const nlohmann::json& j, const std::string& file, double* x, double* y);

}  // namespace terrasynth::detail
