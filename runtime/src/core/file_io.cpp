#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "terrasynth/heightfield_io.h"

namespace terrasynth {

Status writeFileAtomically(const std::string& path, const std::string& bytes) {
    // Same folder as the target so rename() stays atomic on one filesystem.
    const std::string temp = path + ".tmp." + std::to_string(::getpid());
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) return Status::error(path + ": cannot create temporary file: " + std::strerror(errno));
    const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
    const bool flushed = std::fflush(f) == 0 && ::fsync(fileno(f)) == 0;
    const bool closed = std::fclose(f) == 0;
    if (written != bytes.size() || !flushed || !closed) {
        std::remove(temp.c_str());
        return Status::error(path + ": write failed (disk full?)");
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::remove(temp.c_str());
        return Status::error(path + ": cannot replace file: " + reason);
    }
    return Status::ok();
}

Result<std::string> readFileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Status::error(path + ": cannot open: " + std::strerror(errno));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) return Status::error(path + ": read error");
    return buffer.str();
}

}  // namespace terrasynth
