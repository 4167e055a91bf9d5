// terrasynth/file_transaction.h: several files replaced together, or not at all.
//
// A heightmap and its JSON sidecar, a project with its masks and its heights: readers must never see
// a new file beside an old partner (a PNG decoded with another file's height range). Every file is
// first written whole to a temporary in its own folder (fsync'ed); nothing visible changes until
// commit(), which renames them into place in the order they were staged (stage the file that
// describes the others, e.g. the sidecar, last). If a rename fails, the files already replaced get
// their previous content back (or disappear if they did not exist), so the set stays as it was.
// A crash during commit() can leave the set mixed but never a partial file under a final name.
// Temporaries are named after the machine, the process and the transaction, so writers of one
// folder never share one and a killed writer's leftovers can be told from a live one's work.
// Folders: a file's missing folders (any depth) are made when it is staged, and removed again, if
// still empty, when the transaction does not commit; a file where a folder should be is an error
// naming it.
//
// Threading: one transaction per thread; not copyable. The destructor removes temporaries that were
// not committed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth {

class FileTransaction {
public:
    FileTransaction() = default;
    ~FileTransaction();
    FileTransaction(const FileTransaction&) = delete;
    FileTransaction& operator=(const FileTransaction&) = delete;

    // Writes `bytes` to a temporary beside `path` (same folder, so the rename is atomic), making the
    // folder first if it is missing. Errors name `path` (a file in the way of its folder, a folder
    // that cannot be made or written, disk full); the transaction then refuses to commit.
    Status stage(const std::string& path, const std::string& bytes);
    // For writers that stream or open files themselves (a 1 GB glTF buffer, an OpenEXR encoder):
    // `write` must create the temporary file whose name it is given, whole, and return an error
    // naming `path` otherwise. The file is then fsync'ed and staged like stage()'s.
    Status stageWith(const std::string& path, const std::function<Status(const std::string& temporary)>& write);
    // What commit() needs of `path`, checked without writing anything (to refuse before spending
    // time on what is to be written): `path` itself is not a folder, and its folder either exists
    // and is writable or can be made (the nearest existing path above it is a writable folder).
    static Status checkTarget(const std::string& path);
    // Whether `file_name` (no folder) is a temporary or backup a transaction made on this machine
    // ("<name>.tmp.<host>.<pid>.<n>", "<name>.bak.<host>.<pid>.<n>") whose process no longer runs:
    // a leftover of a killed writer, safe to delete. Another machine's or a live process's is not.
    static bool isStaleTemporary(const std::string& file_name);
    // Renames every staged file into place, in staging order. On error the previous files are back
    // and the message names the file that could not be replaced. Call once.
    Status commit();
    // Paths staged so far, in order.
    std::vector<std::string> paths() const;

private:
    struct Staged {
        std::string path, temp;
    };
    void discard();
    Status makeFolderOf(const std::string& path);
    std::vector<Staged> staged_;
    std::vector<std::string> made_folders_;  // outermost first; removed by discard() when empty
    Status failed_ = Status::ok();
    bool done_ = false;
};

}  // namespace terrasynth
