#include "test_support.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "terrasynth/heightfield_io.h"

namespace terrasynth::test {
namespace {
std::string env(const char* name, const char* fallback) {
    const char* v = std::getenv(name);
    return v && *v ? v : fallback;
}
// PoCL caches compiled kernels; keep that cache inside the build tree, not in $HOME.
const bool kPoclCacheSet = [] {
    ::setenv("POCL_CACHE_DIR", TERRASYNTH_TEST_POCL_CACHE, /*overwrite=*/0);
    return true;
}();
}  // namespace

std::string dataDir() { return env("TERRASYNTH_DATA_DIR", TERRASYNTH_TEST_DATA_DIR); }
std::string sharedExemplarsDir() { return env("TERRASYNTH_SHARED_EXEMPLARS", TERRASYNTH_TEST_SHARED_EXEMPLARS); }
std::string binDir() { return env("TERRASYNTH_BIN_DIR", TERRASYNTH_TEST_BIN_DIR); }

CliRun runTerrasynth(const std::string& args) { return runCommand(binDir() + "/terrasynth " + args); }

CliRun runCommand(const std::string& command_line) {
    CliRun r;
    FILE* pipe = ::popen((command_line + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.out.append(buffer, n);
    const int status = ::pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

bool terrasynthBuilt() { return ::access((binDir() + "/terrasynth").c_str(), X_OK) == 0; }

std::string scratchDir(const std::string& name) {
    const std::string dir = env("TERRASYNTH_TEST_TMP", TERRASYNTH_TEST_TMP) + "/" + name;
    std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str());
    return dir;
}

std::string tmpPath(const std::string& name) { return env("TERRASYNTH_TEST_TMP", TERRASYNTH_TEST_TMP) + "/" + name; }

Heightfield loadExemplarField(const std::string& stem) {
    std::string path = dataDir() + "/exemplars/" + stem + ".png";
    if (::access(path.c_str(), R_OK) != 0) path = sharedExemplarsDir() + "/" + stem + ".png";
    auto exemplar = readExemplar(path);
    if (!exemplar) {
        ADD_FAILURE() << exemplar.message();
        return Heightfield(1, 1, 1.0);
    }
    return exemplar->field;
}

bool haveProgram(const std::string& name) {
    return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

std::string xvfbPrefix() {
    const char* display = std::getenv("DISPLAY");
    if (display && *display) return "";
    return "xvfb-run -a -s '-screen 0 1280x720x24' ";
}

int rerunUnderXvfbUnlessDisplay(const std::string& gtest_filter) {
    const char* display = std::getenv("DISPLAY");
    if (display && *display) return kHaveDisplay;
    if (std::getenv("TERRASYNTH_RENDER_CHILD")) {
        ADD_FAILURE() << "xvfb-run gave no DISPLAY";
        return 1;
    }
    if (!haveProgram("xvfb-run")) return kNoXvfb;
    char self[4096] = {};
    if (::readlink("/proc/self/exe", self, sizeof self - 1) <= 0) return 1;
    const std::string cmd = "TERRASYNTH_RENDER_CHILD=1 " + xvfbPrefix() + "'" + self +
                            "' --gtest_filter='" + gtest_filter + "'";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

bool canMountPrivately() {
    return std::system("unshare -rm sh -c 'mount -t tmpfs -o size=64k tmpfs /mnt' >/dev/null 2>&1") == 0;
}

std::string rerunOnAPrivateTmpfs(const std::string& gtest_filter, const std::string& scratch_name,
                                 const std::string& size, int* rc) {
    *rc = 0;
    if (const char* mounted = std::getenv("TERRASYNTH_TEST_PRIVATE_TMPFS")) return mounted;
    if (!canMountPrivately()) {
        *rc = kNoPrivateMount;
        return "";
    }
    const std::string small = scratchDir(scratch_name) + "/small";
    if (::mkdir(small.c_str(), 0755) != 0) {
        ADD_FAILURE() << "cannot make " << small;
        *rc = 1;
        return "";
    }
    char self[4096] = {};
    if (::readlink("/proc/self/exe", self, sizeof self - 1) <= 0) {
        *rc = 1;
        return "";
    }
    const std::string command = "unshare -rm sh -c \"mount -t tmpfs -o size=" + size + " tmpfs '" + small +
                                "' && TERRASYNTH_TEST_PRIVATE_TMPFS='" + small + "' exec '" + self +
                                "' --gtest_filter=" + gtest_filter + "\"";
    const int status = std::system(command.c_str());
    *rc = WIFEXITED(status) ? WEXITSTATUS(status) : 1;
    return "";
}

Heightfield crop(const Heightfield& field, int x0, int y0, int w, int h) {
    Heightfield out(w, h, field.meters_per_pixel_x);
    out.meters_per_pixel_y = field.meters_per_pixel_y;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.at(x, y) = field.at(x0 + x, y0 + y);
    return out;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> filesUnder(const std::string& dir) {
    std::vector<std::string> out;
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return out;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir, ec))
        if (e.is_regular_file()) out.push_back(std::filesystem::relative(e.path(), dir).string());
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace terrasynth::test

namespace terrasynth::test {
std::string defaultDatabasePath() { return tmpPath("default.tsdb"); }

std::string defaultDatabaseProject(const std::string& dir, int seed) {
    defaultDatabase();
    const nlohmann::json project = {{"format", "terrasynth-project"}, {"version", 1},
                                    {"database", defaultDatabasePath()}, {"size", {1024, 1024}},
                                    {"synthesis", {{"seed", seed}}}};
    const std::string path = dir + "/world.tsyn";
    std::ofstream(path) << project.dump(1);
    return path;
}

namespace {
std::shared_ptr<const ExemplarDatabase> cachedDatabase(const std::string& inputs, const std::string& cache) {
    auto loaded = loadOrBuildDatabase({inputs}, DatabaseBuildOptions{}, cache);
    if (!loaded) {
        ADD_FAILURE() << loaded.message();
        return nullptr;
    }
    return loaded.value();
}
}  // namespace

std::shared_ptr<const ExemplarDatabase> defaultDatabase() {
    static std::shared_ptr<const ExemplarDatabase> db = cachedDatabase(dataDir() + "/exemplars", defaultDatabasePath());
    return db;
}

std::shared_ptr<const ExemplarDatabase> sharedDatabase() {
    static std::shared_ptr<const ExemplarDatabase> db =
        cachedDatabase(sharedExemplarsDir(), env("TERRASYNTH_TEST_TMP", TERRASYNTH_TEST_TMP) + std::string("/shared.tsdb"));
    return db;
}
}  // namespace terrasynth::test
