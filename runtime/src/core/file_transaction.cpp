// FileTransaction: temporaries first, renames last; previous files kept as hard links until the
// whole set is in place, so a failed rename can put them back without a moment where they are gone.
#include "terrasynth/file_transaction.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/paths.h"
#include "terrasynth/guard.h"

namespace terrasynth {
namespace {

// Unique per process and transaction, so concurrent writers of one folder never share a temporary.
std::string uniqueSuffix() {
    static std::atomic<unsigned long> counter{0};
    return "." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

Status writeWhole(const std::string& temp, const std::string& path, const std::string& bytes) {
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) return Status::error(path + ": cannot create a temporary file beside it: " + std::strerror(errno));
    const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
    const bool flushed = std::fflush(f) == 0 && ::fsync(fileno(f)) == 0;
    const bool closed = std::fclose(f) == 0;
    if (written != bytes.size() || !flushed || !closed) {
        std::remove(temp.c_str());
        return Status::error(path + ": write failed (disk full?)");
    }
    return Status::ok();
}

// Flushes a file written by someone else to disk, so a rename never exposes unwritten blocks.
bool syncFile(const std::string& temp) {
    const int fd = ::open(temp.c_str(), O_RDONLY);
    if (fd < 0) return false;
    const bool synced = ::fsync(fd) == 0;
    return ::close(fd) == 0 && synced;
}

bool exists(const std::string& path) {
    struct stat st;
    return ::lstat(path.c_str(), &st) == 0;
}

}  // namespace

FileTransaction::~FileTransaction() {
    if (!done_) discard();
}

void FileTransaction::discard() {
    for (const Staged& s : staged_) std::remove(s.temp.c_str());
    staged_.clear();
}

Status FileTransaction::stage(const std::string& path, const std::string& bytes) {
    TERRASYNTH_REQUIRE(!done_, "FileTransaction::stage after commit");
    if (!failed_) return failed_;
    const std::string temp = path + ".tmp" + uniqueSuffix();
    if (Status s = writeWhole(temp, path, bytes); !s) {
        failed_ = s;
        return s;
    }
    staged_.push_back({path, temp});
    return Status::ok();
}

Status FileTransaction::stageWith(const std::string& path,
                                  const std::function<Status(const std::string& temporary)>& write) {
    TERRASYNTH_REQUIRE(!done_, "FileTransaction::stageWith after commit");
    if (!failed_) return failed_;
    const std::string temp = path + ".tmp" + uniqueSuffix();
    // Whatever the writer throws (an encoder's exception) becomes the error, and its temporary goes.
    Status s = guarded(path, [&] { return write(temp); });
    if (s && !syncFile(temp)) s = Status::error(path + ": write failed (disk full?)");
    if (!s) {
        std::remove(temp.c_str());
        failed_ = s;
        return s;
    }
    staged_.push_back({path, temp});
    return Status::ok();
}

Status FileTransaction::checkTarget(const std::string& path) {
    if (path.empty()) return Status::error("an empty output file name");
    struct stat st;
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return Status::error(path + ": is a folder");
    const std::string folder = detail::folderOf(path);
    if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
        return Status::error(path + ": the folder " + folder + " does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
        return Status::error(path + ": cannot write in " + folder + ": " + std::strerror(errno));
    return Status::ok();
}

std::vector<std::string> FileTransaction::paths() const {
    std::vector<std::string> out;
    for (const Staged& s : staged_) out.push_back(s.path);
    return out;
}

Status FileTransaction::commit() {
    TERRASYNTH_REQUIRE(!done_, "FileTransaction::commit called twice");
    done_ = true;
    if (!failed_) {
        discard();
        return failed_;
    }
    // Keep each previous file as a hard link, so it survives its replacement and can come back.
    struct Replaced {
        std::string path, backup;  // backup empty: there was no previous file
    };
    std::vector<Replaced> replaced;
    auto rollback = [&] {
        for (auto it = replaced.rbegin(); it != replaced.rend(); ++it) {
            if (it->backup.empty()) std::remove(it->path.c_str());
            else std::rename(it->backup.c_str(), it->path.c_str());
        }
    };
    for (size_t i = 0; i < staged_.size(); ++i) {
        const Staged s = staged_[i];  // a copy: discard() below empties staged_
        std::string backup;
        if (exists(s.path)) {
            backup = s.path + ".bak" + uniqueSuffix();
            if (::link(s.path.c_str(), backup.c_str()) != 0) {
                const std::string reason = std::strerror(errno);
                rollback();
                discard();
                return Status::error(s.path + ": cannot keep the previous file while replacing it: " + reason);
            }
        }
        if (std::rename(s.temp.c_str(), s.path.c_str()) != 0) {
            const std::string reason = std::strerror(errno);
            if (!backup.empty()) std::remove(backup.c_str());
            rollback();
            discard();
            return Status::error(s.path + ": cannot replace the file: " + reason);
        }
        replaced.push_back({s.path, backup});
    }
    for (const Replaced& r : replaced)
        if (!r.backup.empty()) std::remove(r.backup.c_str());
    staged_.clear();
    return Status::ok();
}

}  // namespace terrasynth
