// Private: the one set of path helpers every module uses (paths are plain '/'-separated strings).
#pragma once

#include <string>

namespace terrasynth::detail {

// "dir/name.png" -> "dir"; "name.png" -> "." (a folder relative paths can be resolved against).
std::string folderOf(const std::string& path);
// `path` as seen from `base_dir`: unchanged when absolute, empty or when base_dir is empty.
std::string resolveRelative(const std::string& base_dir, const std::string& path);
// "dir/name.png" -> "name.png"
std::string baseName(const std::string& path);
// "dir/name.png" -> "name"
std::string fileStem(const std::string& path);
// "dir/name.PNG" -> ".png"; "" when the file name has no dot.
std::string lowerExtension(const std::string& path);
// Case-insensitive test of the extension, `ext` in lower case with its dot: hasExtension(p, ".glb").
bool hasExtension(const std::string& path, const char* ext);
// "dir/name.png" -> "dir/name.json"
std::string sidecarPathFor(const std::string& path);
// Whether anything (file, folder, link) exists at `path`.
bool pathExists(const std::string& path);
// "dir/name.png" -> "dir/name" + suffix (the extension replaced; appended when there is none).
std::string replaceExtension(const std::string& path, const std::string& suffix);

// `path` made absolute against the current directory (no symlinks resolved); "" stays "".
std::string absolutePath(const std::string& path);
// `path` as written in a file that lives in `folder`: relative when it lies inside that folder,
// otherwise absolute (so the file can be moved with what it names, and read from anywhere).
std::string pathForFileIn(const std::string& folder, const std::string& path);

}  // namespace terrasynth::detail
