#include "fuzz_support.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace terrasynth::fuzz {

const std::string& scratchDir() {
    static const std::string dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string d = std::string(tmp && *tmp ? tmp : "/tmp") + "/terrasynth_fuzz." + std::to_string(::getpid());
        ::mkdir(d.c_str(), 0700);
        return d;
    }();
    return dir;
}

void writeFile(const std::string& path, const std::string& bytes) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fclose(f) != 0) {
        std::perror(path.c_str());
        std::abort();
    }
}

void splitInput(const uint8_t* data, size_t size, std::string* first, std::string* rest) {
    if (size < 2) {
        *first = std::string(reinterpret_cast<const char*>(data), size);
        rest->clear();
        return;
    }
    const size_t n = std::min<size_t>(size - 2, data[0] | (size_t(data[1]) << 8));
    first->assign(reinterpret_cast<const char*>(data + 2), n);
    rest->assign(reinterpret_cast<const char*>(data + 2 + n), size - 2 - n);
}

}  // namespace terrasynth::fuzz
