// FileTransaction: several files replaced together or not at all, on a real folder.
#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>

#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield_io.h"
#include "test_support.h"

namespace terrasynth {
namespace {

std::string read(const std::string& path) {
    auto bytes = readFileBytes(path);
    return bytes ? *bytes : std::string("<missing>");
}

// Names in `dir`, to check that no temporary or backup is left behind.
std::vector<std::string> entries(const std::string& dir) {
    std::vector<std::string> names;
    if (DIR* d = opendir(dir.c_str())) {
        while (dirent* e = readdir(d))
            if (e->d_name[0] != '.') names.push_back(e->d_name);
        closedir(d);
    }
    std::sort(names.begin(), names.end());
    return names;
}

TEST(FileTransaction, ReplacesEveryFileOnCommit) {
    const std::string dir = test::scratchDir("transaction_commit");
    ASSERT_TRUE(writeFileAtomically(dir + "/a.png", "old a"));
    FileTransaction t;
    ASSERT_TRUE(t.stage(dir + "/a.png", "new a"));
    ASSERT_TRUE(t.stage(dir + "/a.json", "new sidecar"));
    EXPECT_EQ(read(dir + "/a.png"), "old a");  // nothing visible before commit
    EXPECT_EQ(read(dir + "/a.json"), "<missing>");
    ASSERT_TRUE(t.commit());
    EXPECT_EQ(read(dir + "/a.png"), "new a");
    EXPECT_EQ(read(dir + "/a.json"), "new sidecar");
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.json", "a.png"}));
}

TEST(FileTransaction, AFailedStageCommitsNothing) {
    const std::string dir = test::scratchDir("transaction_stage");
    ASSERT_TRUE(writeFileAtomically(dir + "/a.png", "old a"));
    FileTransaction t;
    ASSERT_TRUE(t.stage(dir + "/a.png", "new a"));
    ASSERT_TRUE(t.stage(dir + "/new/a.json", "sidecar"));  // its folder made for it
    EXPECT_EQ(entries(dir + "/new").size(), 1u);  // the folder, holding the sidecar's temporary
    // A file where a folder should be: the error names the file in the way.
    Status bad = t.stage(dir + "/a.png/more/a.json", "sidecar");
    EXPECT_FALSE(bad);
    EXPECT_NE(bad.message().find(dir + "/a.png/more/a.json: " + dir + "/a.png is a file, not a folder"), std::string::npos)
        << bad.message();
    EXPECT_FALSE(t.commit());
    EXPECT_EQ(read(dir + "/a.png"), "old a");
    // The folder made for the uncommitted sidecar went with it.
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.png"}));
}

TEST(FileTransaction, MakesTheMissingFoldersOfItsFiles) {
    const std::string dir = test::scratchDir("transaction_folders");
    ASSERT_TRUE(FileTransaction::checkTarget(dir + "/a/b/c/x.png"));  // checks, makes nothing
    EXPECT_TRUE(entries(dir).empty());
    FileTransaction t;
    ASSERT_TRUE(t.stage(dir + "/a/b/c/x.png", "x"));
    ASSERT_TRUE(t.stage(dir + "/a/y.json", "y"));
    ASSERT_TRUE(t.stage(dir + "/a/b/../d/z.bin", "z"));  // ".." through a folder made a moment ago
    EXPECT_EQ(read(dir + "/a/b/c/x.png"), "<missing>");  // the folders are there, the files not yet
    EXPECT_EQ(entries(dir + "/a/b/c").size(), 1u);      // only x.png's temporary
    ASSERT_TRUE(t.commit());
    EXPECT_EQ(read(dir + "/a/b/c/x.png"), "x");
    EXPECT_EQ(read(dir + "/a/y.json"), "y");
    EXPECT_EQ(read(dir + "/a/d/z.bin"), "z");
    EXPECT_EQ(entries(dir + "/a"), (std::vector<std::string>{"b", "d", "y.json"}));
    EXPECT_EQ(entries(dir + "/a/b/c"), (std::vector<std::string>{"x.png"}));
    // The one-file writer goes through the same path.
    ASSERT_TRUE(writeFileAtomically(dir + "/e/f/w.txt", "w"));
    EXPECT_EQ(read(dir + "/e/f/w.txt"), "w");
}

TEST(FileTransaction, AFileInTheWayOfAFolderIsNamed) {
    const std::string dir = test::scratchDir("transaction_file_in_the_way");
    ASSERT_TRUE(writeFileAtomically(dir + "/plain", "a file"));
    for (const std::string& target : {dir + "/plain/x.png", dir + "/plain/deeper/still/x.png"}) {
        const std::string expected = target + ": " + dir + "/plain is a file, not a folder";
        const Status checked = FileTransaction::checkTarget(target);
        ASSERT_FALSE(checked) << target;
        EXPECT_EQ(checked.message(), expected);
        FileTransaction t;
        const Status staged = t.stage(target, "x");
        ASSERT_FALSE(staged) << target;
        EXPECT_EQ(staged.message(), expected);
        EXPECT_FALSE(t.commit());
        const Status written = writeFileAtomically(target, "x");
        EXPECT_EQ(written.message(), expected);
    }
    EXPECT_EQ(read(dir + "/plain"), "a file");
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"plain"}));
}

TEST(FileTransaction, OnlyTheEmptyFoldersItMadeGoWhenItDoesNotCommit) {
    const std::string dir = test::scratchDir("transaction_folders_abandoned");
    ASSERT_EQ(::mkdir((dir + "/kept").c_str(), 0755), 0);  // there before: never removed
    {
        FileTransaction t;
        ASSERT_TRUE(t.stage(dir + "/kept/new/deep/x.png", "x"));
        ASSERT_TRUE(t.stage(dir + "/other/y.png", "y"));
        // Someone else writes into one of the made folders meanwhile: that one (and those above it) stay.
        ASSERT_TRUE(writeFileAtomically(dir + "/other/theirs.txt", "theirs"));
    }
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"kept", "other"}));
    EXPECT_TRUE(entries(dir + "/kept").empty());
    EXPECT_EQ(entries(dir + "/other"), (std::vector<std::string>{"theirs.txt"}));
}

TEST(FileTransaction, AFailedRenamePutsThePreviousFilesBack) {
    const std::string dir = test::scratchDir("transaction_rename");
    ASSERT_TRUE(writeFileAtomically(dir + "/a.png", "old a"));
    // A non-empty folder where the sidecar should go: rename() cannot replace it.
    ASSERT_EQ(::mkdir((dir + "/a.json").c_str(), 0755), 0);
    ASSERT_TRUE(writeFileAtomically(dir + "/a.json/inside", "x"));
    FileTransaction t;
    ASSERT_TRUE(t.stage(dir + "/a.png", "new a"));
    ASSERT_TRUE(t.stage(dir + "/b.png", "new b"));
    ASSERT_TRUE(t.stage(dir + "/new/c.png", "new c"));
    ASSERT_TRUE(t.stage(dir + "/a.json", "new sidecar"));
    Status s = t.commit();
    ASSERT_FALSE(s);
    EXPECT_NE(s.message().find("a.json"), std::string::npos) << s.message();
    EXPECT_EQ(read(dir + "/a.png"), "old a");      // restored
    EXPECT_EQ(read(dir + "/b.png"), "<missing>");  // did not exist before: removed again
    // new/c.png was in place a moment: it and its folder are gone again.
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.json", "a.png"}));
}

TEST(FileTransaction, UncommittedTemporariesAreRemoved) {
    const std::string dir = test::scratchDir("transaction_abandon");
    {
        FileTransaction t;
        ASSERT_TRUE(t.stage(dir + "/a.png", "new a"));
    }
    EXPECT_TRUE(entries(dir).empty());
}

}  // namespace
}  // namespace terrasynth
