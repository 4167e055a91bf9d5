// The files one command will write, checked together before any work is done: every folder exists
// and is writable, no output is a folder, and no two outputs (sidecars included) are the same file.
// Written afterwards through one FileTransaction, so either all of them change or none.
#pragma once

#include <string>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth::cli {

struct PlannedOutput {
    std::string option;  // how the user named it, e.g. "--preview"
    std::string path;
};

Status checkOutputs(const std::vector<PlannedOutput>& outputs);

// "dir/name.png" -> "dir/name.json": the sidecar beside a heightmap or sources map.
std::string sidecarOf(const std::string& path);
// Case-insensitive: hasSuffix("A.PNG", ".png").
bool hasSuffix(const std::string& path, const std::string& lower_suffix);

}  // namespace terrasynth::cli
