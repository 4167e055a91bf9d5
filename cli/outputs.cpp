#include "outputs.h"

#include <climits>
#include <cstdlib>

#include <algorithm>
#include <cctype>

#include "terrasynth/file_transaction.h"

namespace terrasynth::cli {
namespace {

// The file's identity for comparison: its folder resolved (links, "..", "./"), then its name.
std::string canonical(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
    char resolved[PATH_MAX];
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    return ::realpath(folder.c_str(), resolved) ? std::string(resolved) + "/" + name : path;
}

}  // namespace

std::string sidecarOf(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    const bool has_dot = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    return (has_dot ? path.substr(0, dot) : path) + ".json";
}

bool hasSuffix(const std::string& path, const std::string& lower_suffix) {
    if (path.size() < lower_suffix.size()) return false;
    return std::equal(lower_suffix.begin(), lower_suffix.end(), path.end() - lower_suffix.size(),
                      [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
}

Status checkOutputs(const std::vector<PlannedOutput>& outputs) {
    for (size_t i = 0; i < outputs.size(); ++i) {
        if (Status s = FileTransaction::checkTarget(outputs[i].path); !s) return s.withContext(outputs[i].option);
        for (size_t j = 0; j < i; ++j)
            if (canonical(outputs[i].path) == canonical(outputs[j].path))
                return Status::error(outputs[i].option + ": " + outputs[i].path + " is also written as " + outputs[j].option);
    }
    return Status::ok();
}

}  // namespace terrasynth::cli
