#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth {

Status writeFileAtomically(const std::string& path, const std::string& bytes) {
    FileTransaction transaction;
    if (Status s = transaction.stage(path, bytes); !s) return s;
    return transaction.commit();
}

Result<std::string> readFileBytes(const std::string& path, uint64_t max_bytes) {
    // Opened without blocking: opening a named pipe for reading otherwise waits for a writer, for
    // ever, before the check below could refuse it.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return Status::error(path + ": cannot open: " + std::strerror(errno));
    // Regular files only: a folder reads as nothing, a device or pipe may never end.
    struct stat st {};
    const bool stated = ::fstat(fd, &st) == 0;
    if (!stated || !S_ISREG(st.st_mode)) {
        ::close(fd);
        return Status::error(path + (stated && S_ISDIR(st.st_mode) ? ": is a folder, not a file" : ": not a regular file"));
    }
    std::FILE* f = ::fdopen(fd, "rb");
    if (!f) {
        ::close(fd);
        return Status::error(path + ": cannot open: " + std::strerror(errno));
    }
    const uint64_t size = static_cast<uint64_t>(st.st_size);
    if (size > max_bytes) {
        std::fclose(f);
        return Status::error(path + ": " + std::to_string(size) + " bytes, more than the " + std::to_string(max_bytes) +
                             " this kind of file may have");
    }
    std::string bytes(size, '\0');
    const size_t got = size ? std::fread(bytes.data(), 1, size, f) : 0;
    const bool failed = std::ferror(f) != 0;
    std::fclose(f);
    if (failed || got != size) return Status::error(path + ": read error (the file changed while reading?)");
    return bytes;
}

}  // namespace terrasynth
