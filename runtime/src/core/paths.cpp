#include "core/paths.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <climits>

#include <unistd.h>

namespace terrasynth::detail {
namespace {

// Position of the extension's dot in the file name, npos when there is none.
size_t extensionDot(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::string::npos;
    return dot;
}

}  // namespace

std::string folderOf(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? std::string("/") : path.substr(0, slash);
}

std::string resolveRelative(const std::string& base_dir, const std::string& path) {
    if (path.empty() || path[0] == '/' || base_dir.empty()) return path;
    return base_dir + "/" + path;
}

std::string baseName(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string fileStem(const std::string& path) {
    const std::string name = baseName(path);
    const size_t dot = name.find_last_of('.');
    return dot == std::string::npos ? name : name.substr(0, dot);
}

std::string lowerExtension(const std::string& path) {
    const size_t dot = extensionDot(path);
    if (dot == std::string::npos) return "";
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

bool hasExtension(const std::string& path, const char* ext) { return lowerExtension(path) == ext; }

std::string replaceExtension(const std::string& path, const std::string& suffix) {
    const size_t dot = extensionDot(path);
    return (dot == std::string::npos ? path : path.substr(0, dot)) + suffix;
}

std::string sidecarPathFor(const std::string& path) { return replaceExtension(path, ".json"); }

std::string absolutePath(const std::string& path) {
    if (path.empty() || path[0] == '/') return path;
    char cwd[PATH_MAX];
    if (!::getcwd(cwd, sizeof cwd)) return path;
    std::string out = cwd;
    for (size_t at = 0; at < path.size();) {
        size_t slash = path.find('/', at);
        if (slash == std::string::npos) slash = path.size();
        const std::string part = path.substr(at, slash - at);
        if (part == "..") out = folderOf(out);
        else if (!part.empty() && part != ".") out += (out == "/" ? "" : "/") + part;
        at = slash + 1;
    }
    return out;
}

std::string pathForFileIn(const std::string& folder, const std::string& path) {
    if (path.empty()) return path;
    const std::string dir = absolutePath(folder), target = absolutePath(path);
    if (target.size() > dir.size() + 1 && target.compare(0, dir.size(), dir) == 0 && target[dir.size()] == '/')
        return target.substr(dir.size() + 1);
    return target;
}

bool pathExists(const std::string& path) {
    struct stat st;
    return ::lstat(path.c_str(), &st) == 0;
}

}  // namespace terrasynth::detail
