// The two databases most tests read (test_support.h), built once into their cache files before those
// tests start: ctest runs these as the setup of the fixtures test_database_default and
// test_database_shared (tests/CMakeLists.txt). Before, the first tests to start each built the same
// database at once: two cores on one 17-exemplar build, six minutes under the sanitizers.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "test_support.h"

using namespace terrasynth;

namespace {

// Exemplar images in `dir` (a database holds one exemplar per readable PNG there).
size_t pngsIn(const std::string& dir) {
    const std::vector<std::string> files = test::filesUnder(dir);
    return std::count_if(files.begin(), files.end(),
                         [](const std::string& f) { return std::filesystem::path(f).extension() == ".png"; });
}

}  // namespace

TEST(TestDatabases, DefaultBuildsAndReloadsFromItsCache) {
    auto db = test::defaultDatabase();
    ASSERT_TRUE(db);
    EXPECT_EQ(db->exemplars.size(), pngsIn(test::dataDir() + "/exemplars"));
    auto reloaded = loadDatabase(test::defaultDatabasePath());
    ASSERT_TRUE(reloaded) << reloaded.message();
    EXPECT_EQ(reloaded.value()->exemplars.size(), db->exemplars.size());
}

TEST(TestDatabases, SharedBuildsFromEverySharedExemplar) {
    auto db = test::sharedDatabase();
    ASSERT_TRUE(db);
    EXPECT_EQ(db->exemplars.size(), pngsIn(test::sharedExemplarsDir()));
}
