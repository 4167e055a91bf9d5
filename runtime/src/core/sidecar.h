// Private: JSON sidecar helpers shared by the exemplar readers and heightfield writers.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/json_reader.h"
#include "core/paths.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/status.h"

namespace terrasynth::detail {

Result<nlohmann::json> readJsonFile(const std::string& path);

// Reads a number field; error names the file and the key.
Result<double> requireNumber(const nlohmann::json& j, const char* key, const std::string& file);
// Reads meters_per_pixel given as a number or [x, y].
Status readSpacing(const nlohmann::json& j, const std::string& file, double* x, double* y);
// Copies terrain_class, source and license (strings; absent or other types read as "").
void readProvenance(const nlohmann::json& j, ExemplarInfo* info);
// Reads the optional "type_mask" (an 8-bit gray PNG of the exemplar's size, relative to the
// sidecar's folder) and "type_names" into `exemplar`.
Status readTypeMask(const nlohmann::json& j, const std::string& sidecar, Exemplar* exemplar);

}  // namespace terrasynth::detail
