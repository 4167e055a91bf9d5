// `terrasynth stats --sources src.png`: which parts of its exemplars a synthesis drew from
// (terrasynth/source_usage.h), read from a `synth --sources` map and its sidecar.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "terrasynth/status.h"

namespace terrasynth::cli {

// Reads the map and its sidecar, re-reads every exemplar it names (paths as recorded in the
// database, relative to the working directory) at the map's spacing, and returns per exemplar its
// output share, pixel share and the share drawn from its flattest 30%. Errors name the file.
Result<nlohmann::json> measureSourcesMap(const std::string& sources_png);
// The same figures as a table on stdout.
void printSourcesReport(const nlohmann::json& report);

}  // namespace terrasynth::cli
