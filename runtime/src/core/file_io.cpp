#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {

Status writeFileAtomically(const std::string& path, const std::string& bytes) {
    FileTransaction transaction;
    if (Status s = transaction.stage(path, bytes); !s) return s;
    return transaction.commit();
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
