// Tests: the names FileTransaction gives its temporaries ("<file>.tmp.<host>.<pid>.<n>"), so a test can
// plant what a dead or a live writer leaves (FileTransaction::isStaleTemporary tells them apart).
#pragma once

#include <unistd.h>

#include <string>

namespace terrasynth::test {

// This machine's name as FileTransaction puts it into temporary names ('.' and '/' as '_').
inline std::string hostTag() {
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    std::string t = name;
    for (char& c : t)
        if (c == '.' || c == '/') c = '_';
    return t;
}

// The temporary that process `pid` writes for `file` (its n-th).
inline std::string temporaryOf(const std::string& file, long pid, int n = 0) {
    return file + ".tmp." + hostTag() + "." + std::to_string(pid) + "." + std::to_string(n);
}

}  // namespace terrasynth::test
