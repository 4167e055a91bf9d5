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
    Status bad = t.stage(dir + "/missing/a.json", "sidecar");
    EXPECT_FALSE(bad);
    EXPECT_NE(bad.message().find("missing/a.json"), std::string::npos) << bad.message();
    EXPECT_FALSE(t.commit());
    EXPECT_EQ(read(dir + "/a.png"), "old a");
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"a.png"}));
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
    ASSERT_TRUE(t.stage(dir + "/a.json", "new sidecar"));
    Status s = t.commit();
    ASSERT_FALSE(s);
    EXPECT_NE(s.message().find("a.json"), std::string::npos) << s.message();
    EXPECT_EQ(read(dir + "/a.png"), "old a");      // restored
    EXPECT_EQ(read(dir + "/b.png"), "<missing>");  // did not exist before: removed again
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
