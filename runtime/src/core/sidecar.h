// Private: JSON sidecar helpers shared by the exemplar readers and heightfield writers.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "terrasynth/status.h"

namespace terrasynth::detail {

// "dir/name.png" -> "dir/name.json"
std::string sidecarPathFor(const std::string& path);
std::string fileStem(const std::string& path);
std::string directoryOf(const std::string& path);  // "" or "dir/"
std::string lowerExtension(const std::string& path);  // ".png"

Result<nlohmann::json> readJsonFile(const std::string& path);

// Reads a number field; error names the file and the key.
Result<double> requireNumber(const nlohmann::json& j, const char* key, const std::string& file);
// Reads an optional number field checked against [lo, hi]: no value when the key is absent, an
// error "<field>: must be a number" / "<field>: must be in [lo, hi], got v" otherwise.
Result<std::optional<double>> readNumberInRange(const nlohmann::json& object, const char* key,
                                                const std::string& field, double lo, double hi);
// Shortest decimal text of v ("0.25", "12").
std::string compactNumber(double v);

// Reads meters_per_pixel given as a number or [x, y].
Status readSpacing(const nlohmann::json& j, const std::string& file, double* x, double* y);

}  // namespace terrasynth::detail
