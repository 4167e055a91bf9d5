// FileTransaction: missing folders and temporaries first, renames last; previous files kept as hard
// links until the whole set is in place, so a failed rename can put them back without a moment where
// they are gone.
#include "terrasynth/file_transaction.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <climits>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/paths.h"
#include "terrasynth/guard.h"

namespace terrasynth {
namespace {

// This machine's name as it goes into file names: no '/' and no '.', so the name parses back.
const std::string& hostTag() {
    static const std::string tag = [] {
        char name[256] = {};
        if (::gethostname(name, sizeof name - 1) != 0 || !name[0]) return std::string("host");
        std::string t = name;
        for (char& c : t)
            if (c == '/' || c == '.') c = '_';
        return t;
    }();
    return tag;
}

// Unique per machine, process and transaction ("<host>.<pid>.<n>"), so concurrent writers of one
// folder, on one machine or several sharing it, never share a temporary, and isStaleTemporary can
// tell a dead writer's leftovers from a live one's work.
std::string uniqueSuffix() {
    static std::atomic<unsigned long> counter{0};
    return "." + hostTag() + "." + std::to_string(::getpid()) + "." + std::to_string(counter++);
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

// The folder `path` goes into, as the nearest path above it that exists (`existing`, which must be a
// folder) and the folders below that one that are missing (`missing`, outermost first). The error
// names `path` and what is in the way.
Status findFolder(const std::string& path, std::string* existing, std::vector<std::string>* missing) {
    std::string folder = detail::folderOf(path);
    struct stat st;
    while (::stat(folder.c_str(), &st) != 0) {
        // ENOTDIR: a file further up; walking on finds it and names it below.
        if (errno != ENOENT && errno != ENOTDIR)
            return Status::error(path + ": cannot look into " + folder + ": " + std::strerror(errno));
        const std::string up = detail::folderOf(folder);
        if (up == folder) return Status::error(path + ": cannot look into " + folder);
        missing->insert(missing->begin(), folder);
        folder = up;
    }
    if (!S_ISDIR(st.st_mode))
        return Status::error(path + ": " + folder + (S_ISREG(st.st_mode) ? " is a file, not a folder" : " is not a folder"));
    *existing = folder;
    return Status::ok();
}

}  // namespace

FileTransaction::~FileTransaction() {
    if (!done_) discard();
}

void FileTransaction::discard() {
    for (const Staged& s : staged_) std::remove(s.temp.c_str());
    staged_.clear();
    // Innermost first; a folder someone else has put something in meanwhile stays (rmdir refuses).
    for (auto it = made_folders_.rbegin(); it != made_folders_.rend(); ++it) ::rmdir(it->c_str());
    made_folders_.clear();
}

Status FileTransaction::makeFolderOf(const std::string& path) {
    std::string existing;
    std::vector<std::string> missing;
    if (Status s = findFolder(path, &existing, &missing); !s) return s;
    for (const std::string& folder : missing) {
        if (::mkdir(folder.c_str(), 0777) == 0) {
            made_folders_.push_back(folder);
            continue;
        }
        const int error = errno;
        struct stat st;
        // Made by another writer meanwhile: as good, and not this transaction's to remove.
        if (error == EEXIST && ::stat(folder.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) continue;
        return Status::error(path + ": cannot make the folder " + folder + ": " + std::strerror(error));
    }
    return Status::ok();
}


Status FileTransaction::stage(const std::string& path, const std::string& bytes) {
    TERRASYNTH_REQUIRE(!done_, "FileTransaction::stage after commit");
    if (!failed_) return failed_;
    if (Status s = makeFolderOf(path); !s) {
        failed_ = s;
        return s;
    }
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
    if (Status s = makeFolderOf(path); !s) {
        failed_ = s;
        return s;
    }
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
    std::string folder;
    std::vector<std::string> missing;  // made by stage()
    if (Status s = findFolder(path, &folder, &missing); !s) return s;
    if (::access(folder.c_str(), W_OK) != 0)
        return Status::error(path + ": cannot write in " + folder + ": " + std::strerror(errno));
    return Status::ok();
}

bool FileTransaction::isStaleTemporary(const std::string& file_name) {
    // "<name>.tmp.<host>.<pid>.<n>" or "<name>.bak.<host>.<pid>.<n>"
    const size_t last = file_name.rfind('.');
    if (last == std::string::npos || last == 0) return false;
    const size_t pid_dot = file_name.rfind('.', last - 1);
    if (pid_dot == std::string::npos || pid_dot == 0) return false;
    const size_t host_dot = file_name.rfind('.', pid_dot - 1);
    if (host_dot == std::string::npos || host_dot < 4) return false;
    const std::string kind = file_name.substr(host_dot - 4, 5);
    if (kind != ".tmp." && kind != ".bak.") return false;
    const std::string host = file_name.substr(host_dot + 1, pid_dot - host_dot - 1);
    const std::string pid_text = file_name.substr(pid_dot + 1, last - pid_dot - 1);
    const std::string counter = file_name.substr(last + 1);
    const auto digits = [](const std::string& t) {
        return !t.empty() && t.size() <= 18 && t.find_first_not_of("0123456789") == std::string::npos;
    };
    if (host != hostTag() || !digits(pid_text) || !digits(counter)) return false;
    const long long pid = std::stoll(pid_text);
    if (pid <= 0 || pid > INT32_MAX || pid == ::getpid()) return false;
    // kill(pid, 0) fails with ESRCH only when no such process exists (EPERM: it exists).
    return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
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
    made_folders_.clear();  // they hold the files now
    return Status::ok();
}

}  // namespace terrasynth
