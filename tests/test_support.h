// Helpers shared by the tests: where the data lives, scratch paths, small real-data crops.
#pragma once

#include <string>
#include <vector>

#include "terrasynth/heightfield.h"

namespace terrasynth::test {

std::string dataDir();             // shipped defaults: <repo>/data
std::string sharedExemplarsDir();  // ../shared/exemplars
std::string binDir();              // built executables
// Runs `<binDir>/terrasynth <args>` through the shell; stdout and stderr together.
struct CliRun {
    int exit_code = -1;
    std::string out;
};
CliRun runTerrasynth(const std::string& args);
// Runs a shell command line; stdout and stderr together.
CliRun runCommand(const std::string& command_line);
bool terrasynthBuilt();
// A fresh, empty scratch directory for one test: <build>/test_tmp/<name>.
std::string scratchDir(const std::string& name);
// <build>/test_tmp/<name>, left as it is (for caches that outlive one run).
std::string tmpPath(const std::string& name);
// Loads a shipped or shared exemplar (by stem, e.g. "orom_alaska") and aborts the test on error.
Heightfield loadExemplarField(const std::string& stem);
// Crop of a field (x0,y0,w,h), same spacing.
Heightfield crop(const Heightfield& field, int x0, int y0, int w, int h);
// The bytes of a file ("" when it cannot be read).
std::string readFile(const std::string& path);
// Every regular file under `dir`, as sorted paths relative to it (empty when dir is absent).
std::vector<std::string> filesUnder(const std::string& dir);

// Tests that open windows (Mesa llvmpipe under Xvfb). With DISPLAY set this returns kHaveDisplay:
// run the test body here. Otherwise the running test binary re-runs itself, filtered to
// `gtest_filter`, under `xvfb-run -a` (screen 1280x720x24) and the child's exit code is returned
// (its output goes to ours); kNoXvfb when xvfb-run is missing. A child without a display fails.
constexpr int kHaveDisplay = -1000, kNoXvfb = -1001;
int rerunUnderXvfbUnlessDisplay(const std::string& gtest_filter);
// At the top of a TEST that needs a window: with a display, go on; otherwise run this test again
// under xvfb-run, check its exit code and return (skip when xvfb-run is missing).
#define TERRASYNTH_NEED_DISPLAY(gtest_filter)                                                   \
    do {                                                                                        \
        const int display_rc = ::terrasynth::test::rerunUnderXvfbUnlessDisplay(gtest_filter);   \
        if (display_rc == ::terrasynth::test::kNoXvfb) GTEST_SKIP() << "no DISPLAY and no xvfb-run"; \
        if (display_rc != ::terrasynth::test::kHaveDisplay) {                                    \
            ASSERT_EQ(display_rc, 0) << "the test under xvfb-run failed (its output is above)"; \
            return;                                                                             \
        }                                                                                       \
    } while (0)
// Tests of a full or read-only disk, on a small filesystem of their own: the running test binary runs
// itself again, filtered to `gtest_filter`, in a private user and mount namespace (unshare -rm) with
// a tmpfs of `size` (mount's size=, e.g. "48m") on a fresh scratch folder `scratch_name`/small.
// Inside that run this returns the folder; outside it returns "" with the run's exit code in *rc, or
// kNoPrivateMount where user namespaces or mounts are refused.
constexpr int kNoPrivateMount = -1002;
// Whether this machine lets a test mount a tmpfs in a private user and mount namespace.
bool canMountPrivately();
std::string rerunOnAPrivateTmpfs(const std::string& gtest_filter, const std::string& scratch_name,
                                 const std::string& size, int* rc);
// At the top of a TEST: `folder` is the private tmpfs's folder here, or the test returns after the
// run inside it (checking its exit code; skipped where no private mount can be made).
#define TERRASYNTH_ON_A_PRIVATE_TMPFS(folder, gtest_filter, scratch_name, size)                        \
    int folder##_rc = 0;                                                                              \
    const std::string folder = ::terrasynth::test::rerunOnAPrivateTmpfs(gtest_filter, scratch_name, size, \
                                                                        &folder##_rc);                \
    if (folder.empty()) {                                                                             \
        if (folder##_rc == ::terrasynth::test::kNoPrivateMount)                                       \
            GTEST_SKIP() << "cannot mount a private tmpfs here (unshare -rm refused)";                \
        ASSERT_EQ(folder##_rc, 0) << "the run inside the private mount failed (its output is above)"; \
        return;                                                                                       \
    }
// "xvfb-run -a -s '-screen 0 1280x720x24' " to prefix a command that opens a window, or "" when
// DISPLAY is already set.
std::string xvfbPrefix();
bool haveProgram(const std::string& name);

}  // namespace terrasynth::test

#include <memory>

#include "terrasynth/database.h"

namespace terrasynth::test {
// The database of the shipped default exemplars, built once and cached in the build tree
// (<build>/test_tmp/default.tsdb, rebuilt when stale) so test executables share it.
std::shared_ptr<const ExemplarDatabase> defaultDatabase();
// Where defaultDatabase() keeps its cache file (valid once defaultDatabase() has been called).
std::string defaultDatabasePath();
// Writes <dir>/world.tsyn: a 1024x1024 project over defaultDatabase() with synthesis seed `seed`;
// returns its path.
std::string defaultDatabaseProject(const std::string& dir, int seed);
// The database of all shared exemplars (../shared/exemplars), built once and cached the same way
// (<build>/test_tmp/shared.tsdb).
std::shared_ptr<const ExemplarDatabase> sharedDatabase();
}  // namespace terrasynth::test
