#include "test_support.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

#include <cstdlib>

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

CliRun runTerrasynth(const std::string& args) {
    CliRun r;
    FILE* pipe = ::popen((binDir() + "/terrasynth " + args + " 2>&1").c_str(), "r");
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

Heightfield crop(const Heightfield& field, int x0, int y0, int w, int h) {
    Heightfield out(w, h, field.meters_per_pixel_x);
    out.meters_per_pixel_y = field.meters_per_pixel_y;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.at(x, y) = field.at(x0 + x, y0 + y);
    return out;
}

}  // namespace terrasynth::test

namespace terrasynth::test {
std::string defaultDatabasePath() { return tmpPath("default.tsdb"); }

std::shared_ptr<const ExemplarDatabase> defaultDatabase() {
    static std::shared_ptr<const ExemplarDatabase> db = [] {
        const std::string cache = defaultDatabasePath();
        auto loaded = loadOrBuildDatabase({dataDir() + "/exemplars"}, DatabaseBuildOptions{}, cache);
        if (!loaded) {
            ADD_FAILURE() << loaded.message();
            return std::shared_ptr<const ExemplarDatabase>();
        }
        return loaded.value();
    }();
    return db;
}
}  // namespace terrasynth::test
