// `terrasynth bake` on a synthesized project: every .glb passes the Khronos validator, the tileset
// loads in a 3D Tiles client (loaders.gl, scripts/check_tileset.mjs) that reaches every tile with
// vertices inside their boxes and errors falling with depth, neighbouring tiles of any LODs leave no
// vertical gap, a killed shard re-run gives the same bytes, and bad input exits 2 leaving nothing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "terrasynth/heightfield_io.h"
#include "test_support.h"
#include "wait_until.h"

using namespace terrasynth;
namespace fs = std::filesystem;

namespace {

std::string repoDir() { return test::dataDir() + "/.."; }

// A project over the shipped exemplars, using the tests' shared database.
std::string writeProject(const std::string& dir) { return test::defaultDatabaseProject(dir, 3); }

test::CliRun bake(const std::string& args) { return test::runTerrasynth("bake " + args + " --progress lines"); }



// Every file of `a` has the same bytes in `b`, and neither has files the other lacks.
void expectSameFiles(const std::string& a, const std::string& b) {
    const auto fa = test::filesUnder(a), fb = test::filesUnder(b);
    ASSERT_EQ(fa, fb);
    int differing = 0;
    for (const std::string& f : fa)
        if (test::readFile(a + "/" + f) != test::readFile(b + "/" + f) && ++differing <= 5) ADD_FAILURE() << f << " differs";
    EXPECT_EQ(differing, 0);
}

int runScript(const std::string& command, std::string* output) {
    // One folder per process: ctest runs the BakeCli tests in parallel, and a shared one was wiped
    // or overwritten by another test mid-run (a check read the other test's validator output).
    const std::string log = test::scratchDir("bake_script_log_" + std::to_string(getpid())) + "/out.txt";
    const int status = std::system((command + " > '" + log + "' 2>&1").c_str());
    *output = test::readFile(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// ---- Reading baked tiles back for the crack check -------------------------------------------

struct Tile {
    std::string name;
    int lod = 0;
    std::vector<double> xyz;  // world x east, y north, z up
    std::vector<uint32_t> tris;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;  // footprint
};

Tile loadTile(const std::string& path) {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    Tile tile;
    tile.name = path;
    if (!loader.LoadBinaryFromFile(&model, &err, &warn, path)) {
        ADD_FAILURE() << path << ": " << err;
        return tile;
    }
    const tinygltf::Value& info = model.nodes[0].extras.Get("terrasynth_tile");
    tile.lod = info.Get("lod").GetNumberAsInt();
    const auto& rt = model.nodes[0].translation;
    for (int child : model.nodes[0].children) {
        const tinygltf::Node& node = model.nodes[child];
        const double s = node.scale.empty() ? 1.0 : node.scale[0];
        const double t[3] = {rt[0] + node.translation[0], rt[1] + node.translation[1], rt[2] + node.translation[2]};
        for (const tinygltf::Primitive& p : model.meshes[node.mesh].primitives) {
            const tinygltf::Accessor& a = model.accessors[p.attributes.at("POSITION")];
            const tinygltf::BufferView& v = model.bufferViews[a.bufferView];
            const uint8_t* data = model.buffers[v.buffer].data.data() + v.byteOffset + a.byteOffset;
            const size_t stride = a.ByteStride(v), base = tile.xyz.size() / 3;
            for (size_t i = 0; i < a.count; ++i) {
                double g[3];
                for (int c = 0; c < 3; ++c) {
                    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
                        float f;
                        std::memcpy(&f, data + i * stride + 4 * c, 4);
                        g[c] = f;
                    } else {
                        uint16_t u;
                        std::memcpy(&u, data + i * stride + 2 * c, 2);
                        g[c] = u;
                    }
                    g[c] = t[c] + s * g[c];
                }
                tile.xyz.insert(tile.xyz.end(), {g[0], -g[2], g[1]});
                tile.x0 = std::min(tile.x0, g[0]), tile.x1 = std::max(tile.x1, g[0]);
                tile.y0 = std::min(tile.y0, -g[2]), tile.y1 = std::max(tile.y1, -g[2]);
            }
            const tinygltf::Accessor& ia = model.accessors[p.indices];
            const tinygltf::BufferView& iv = model.bufferViews[ia.bufferView];
            const uint8_t* idata = model.buffers[iv.buffer].data.data() + iv.byteOffset + ia.byteOffset;
            for (size_t i = 0; i < ia.count; ++i) {
                uint32_t index;
                if (ia.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) std::memcpy(&index, idata + 4 * i, 4);
                else {
                    uint16_t u;
                    std::memcpy(&u, idata + 2 * i, 2);
                    index = u;
                }
                tile.tris.push_back(static_cast<uint32_t>(base) + index);
            }
        }
    }
    return tile;
}

// The vertical extent [lo, hi] of a tile's triangles (surface and skirt) on the vertical line through
// the point at `t` along the boundary line {axis = value}; false when none reaches it.
bool coverageAt(const Tile& tile, int axis, double value, double t, double tol, double* lo, double* hi) {
    *lo = INFINITY, *hi = -INFINITY;
    const int along = 1 - axis;
    for (size_t k = 0; k < tile.tris.size(); k += 3) {
        // The triangle's vertices on the line, as (t, z) points.
        double pt[3][2];
        int n = 0;
        for (int c = 0; c < 3; ++c) {
            const double* p = &tile.xyz[3 * tile.tris[k + c]];
            if (std::fabs(p[axis] - value) < tol) pt[n][0] = p[along], pt[n][1] = p[2], ++n;
        }
        if (n < 2) continue;
        // The on-line part is the segment or triangle of those points; cut it at t.
        for (int a = 0; a < n; ++a)
            for (int b = a + 1; b < n; ++b) {
                const double ta = pt[a][0], tb = pt[b][0];
                if (t < std::min(ta, tb) - tol || t > std::max(ta, tb) + tol) continue;
                const double z = std::fabs(tb - ta) < tol ? pt[a][1] : pt[a][1] + (pt[b][1] - pt[a][1]) * (t - ta) / (tb - ta);
                *lo = std::min({*lo, z, std::fabs(tb - ta) < tol ? std::min(pt[a][1], pt[b][1]) : z});
                *hi = std::max({*hi, z, std::fabs(tb - ta) < tol ? std::max(pt[a][1], pt[b][1]) : z});
            }
    }
    return *lo <= *hi;
}

struct CrackReport {
    int pairs = 0, mixed_lod_pairs = 0, points = 0, gaps = 0;
    double worst_overlap_m = INFINITY;  // smallest overlap of two tiles' coverage at a point
    std::string first_gap;
};

// Every pair of tiles whose footprints share a stretch of border, whatever their LODs (a client
// may draw any two of them side by side): at every vertex on that stretch and between them, the
// two tiles' vertical coverage (surface point plus skirt) must overlap.
CrackReport checkCracks(const std::vector<Tile>& tiles, double spacing) {
    CrackReport report;
    const double tol = 1e-3 * spacing;
    for (size_t a = 0; a < tiles.size(); ++a)
        for (size_t b = 0; b < tiles.size(); ++b) {
            if (a == b) continue;
            const Tile &A = tiles[a], &B = tiles[b];
            // B east of A (shared x), or B south of A (shared y).
            for (int axis = 0; axis < 2; ++axis) {
                const double line = axis == 0 ? A.x1 : A.y0;
                const double other = axis == 0 ? B.x0 : B.y1;
                if (std::fabs(line - other) > tol) continue;
                const double t0 = std::max(axis == 0 ? A.y0 : A.x0, axis == 0 ? B.y0 : B.x0);
                const double t1 = std::min(axis == 0 ? A.y1 : A.x1, axis == 0 ? B.y1 : B.x1);
                if (t1 - t0 < tol) continue;
                ++report.pairs;
                report.mixed_lod_pairs += A.lod != B.lod;
                std::vector<double> ts;
                for (const Tile* tile : {&A, &B})
                    for (size_t v = 0; v < tile->xyz.size(); v += 3)
                        if (std::fabs(tile->xyz[v + axis] - line) < tol && tile->xyz[v + 1 - axis] >= t0 - tol &&
                            tile->xyz[v + 1 - axis] <= t1 + tol)
                            ts.push_back(tile->xyz[v + 1 - axis]);
                std::sort(ts.begin(), ts.end());
                ts.erase(std::unique(ts.begin(), ts.end(), [&](double p, double q) { return q - p < tol; }), ts.end());
                const size_t n = ts.size();
                for (size_t k = 0; k + 1 < n; ++k) ts.push_back(0.5 * (ts[k] + ts[k + 1]));
                for (double t : ts) {
                    double alo, ahi, blo, bhi;
                    const bool ca = coverageAt(A, axis, line, t, tol, &alo, &ahi);
                    const bool cb = coverageAt(B, axis, line, t, tol, &blo, &bhi);
                    ++report.points;
                    const double overlap = std::min(ahi, bhi) - std::max(alo, blo);
                    if (!ca || !cb || overlap < -1e-3) {
                        if (report.gaps++ == 0)
                            report.first_gap = A.name + " / " + B.name + " at " + std::to_string(t) + ": [" + std::to_string(alo) +
                                               ", " + std::to_string(ahi) + "] vs [" + std::to_string(blo) + ", " + std::to_string(bhi) + "]";
                    }
                    if (ca && cb) report.worst_overlap_m = std::min(report.worst_overlap_m, overlap);
                }
            }
        }
    return report;
}

class BakeCli : public ::testing::Test {
protected:
    void SetUp() override {
        if (!test::terrasynthBuilt()) GTEST_SKIP() << "terrasynth CLI not built";
    }
};

}  // namespace

TEST_F(BakeCli, TilesetPassesTheValidatorTheClientAndTheCrackCheck) {
    const std::string dir = test::scratchDir("bake_cli_full");
    const std::string project = writeProject(dir), world = dir + "/world";
    // 4 LODs of 128-quad tiles over a region that is not tile-aligned, so edge tiles are clipped.
    const test::CliRun r = bake("'" + project + "' -o '" + world + "' --region 40,-24,700,600 --tile 128 --levels 4 "
                                "--quantize --heightmaps f32 --masks");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("tiles/s"), std::string::npos) << r.out;  // progress on stderr
    EXPECT_NE(r.out.find("wrote"), std::string::npos) << r.out;

    std::vector<std::string> glbs;
    for (const std::string& f : test::filesUnder(world))
        if (f.size() > 4 && f.substr(f.size() - 4) == ".glb") glbs.push_back(world + "/" + f);
    ASSERT_GT(glbs.size(), 40u);

    if (std::system("command -v node > /dev/null 2>&1") != 0) {
        ADD_FAILURE() << "node is not installed (scripts/setup.sh installs it)";
    } else {
        std::string command = "'" + repoDir() + "/scripts/validate_gltf.sh'", output;
        for (const std::string& g : glbs) command += " '" + g + "'";
        EXPECT_EQ(runScript(command, &output), 0) << output;
        EXPECT_EQ(output.find(" 0 errors") == std::string::npos, false);
        output.clear();
        EXPECT_EQ(runScript("node '" + repoDir() + "/scripts/check_tileset.mjs' '" + world + "'", &output), 0) << output;
        EXPECT_NE(output.find(std::to_string(glbs.size()) + " contents loaded"), std::string::npos) << output;
    }

    std::vector<Tile> tiles;
    for (const std::string& g : glbs) tiles.push_back(loadTile(g));
    const CrackReport cracks = checkCracks(tiles, 92.6);
    EXPECT_GT(cracks.mixed_lod_pairs, 50);
    EXPECT_EQ(cracks.gaps, 0) << cracks.first_gap;
    std::printf("crack check: %d neighbouring pairs (%d of mixed LOD), %d points, smallest coverage overlap %.1f m\n",
                cracks.pairs, cracks.mixed_lod_pairs, cracks.points, cracks.worst_overlap_m);

    // Leaf heightmaps (float32, exact): neighbours share their edge samples, bit for bit.
    // Leaves are at depth 4 (one empty level above the two coarsest tiles); x = i, y = 7 - j.
    auto west = readExemplar(world + "/tiles/4/1/6.f32");
    auto east = readExemplar(world + "/tiles/4/2/6.f32");
    ASSERT_TRUE(west) << west.message();
    ASSERT_TRUE(east) << east.message();
    ASSERT_EQ(west->field.height, east->field.height);
    for (int y = 0; y < west->field.height; ++y) ASSERT_EQ(west->field.at(west->field.width - 1, y), east->field.at(0, y));
    int masks = 0;
    for (const std::string& f : test::filesUnder(world + "/tiles/4/1")) masks += f.find("6.mask_") == 0;
    EXPECT_GE(masks, 2);
}

namespace {

bool allGlbsComplete(const std::string& world, int* count) {
    *count = 0;
    for (const std::string& f : test::filesUnder(world)) {
        if (f.size() < 4 || f.substr(f.size() - 4) != ".glb") continue;
        ++*count;
        const std::string bytes = test::readFile(world + "/" + f);
        uint32_t length = 0;
        if (bytes.size() >= 12) std::memcpy(&length, bytes.data() + 8, 4);
        if (bytes.size() < 12 || bytes.compare(0, 4, "glTF") != 0 || length != bytes.size()) return false;
    }
    return true;
}

int countGlbs(const std::string& world) {
    int n = 0;
    if (!fs::exists(world + "/tiles")) return 0;
    for (const auto& e : fs::recursive_directory_iterator(world + "/tiles", fs::directory_options::skip_permission_denied))
        n += e.path().extension() == ".glb";
    return n;
}

}  // namespace

TEST_F(BakeCli, KilledShardRerunGivesTheSameBytes) {
    const std::string dir = test::scratchDir("bake_cli_kill");
    const std::string project = writeProject(dir);
    const std::string options = " --region 0,0,1025,769 --tile 128 --levels 3 --quantize";
    const test::CliRun whole = bake("'" + project + "' -o '" + dir + "/whole'" + options);
    ASSERT_EQ(whole.exit_code, 0) << whole.out;

    // Shard 0 of 2 on one thread, killed (SIGKILL) once it has written a few tiles.
    const std::string sharded = dir + "/sharded";
    // A subshell waits for it, so once killed it is reaped and kill(pid, 0) fails.
    const std::string start = "(" + test::binDir() + "/terrasynth bake '" + project + "' -o '" + sharded + "'" + options +
                              " --shard 0/2 --threads 1 --progress none > '" + dir + "/shard0.log' 2>&1 & echo $! > '" +
                              dir + "/shard0.pid'; wait $!) &";
    ASSERT_EQ(std::system(start.c_str()), 0);
    ASSERT_TRUE(test::waitUntil([&] { return !test::readFile(dir + "/shard0.pid").empty(); }));
    const pid_t pid = std::stoi(test::readFile(dir + "/shard0.pid"));
    ASSERT_TRUE(test::waitUntil([&] { return countGlbs(sharded) >= 3; }, std::chrono::minutes(10),
                                std::chrono::milliseconds(10)));
    ASSERT_EQ(::kill(pid, SIGKILL), 0) << "shard 0 ended before it could be killed";
    ASSERT_TRUE(test::waitUntil([&] { return ::kill(pid, 0) != 0; })) << "shard 0 outlived SIGKILL";
    int written = 0;
    EXPECT_TRUE(allGlbsComplete(sharded, &written)) << "a partial .glb under its final name";
    const test::CliRun shard1 = bake("'" + project + "' -o '" + sharded + "'" + options + " --shard 1/2");
    ASSERT_EQ(shard1.exit_code, 0) << shard1.out;
    const test::CliRun early_merge = test::runTerrasynth("bake --merge '" + sharded + "'");
    EXPECT_EQ(early_merge.exit_code, 2) << early_merge.out;  // shard 0's tiles are missing
    EXPECT_NE(early_merge.out.find("missing"), std::string::npos) << early_merge.out;

    const test::CliRun rerun = bake("'" + project + "' -o '" + sharded + "'" + options + " --shard 0/2");
    ASSERT_EQ(rerun.exit_code, 0) << rerun.out;
    EXPECT_NE(rerun.out.find(std::to_string(written) + " already complete"), std::string::npos) << rerun.out;
    const test::CliRun merge = test::runTerrasynth("bake --merge '" + sharded + "'");
    ASSERT_EQ(merge.exit_code, 0) << merge.out;
    for (const std::string& f : test::filesUnder(sharded)) EXPECT_EQ(f.find(".tmp."), std::string::npos) << f;
    expectSameFiles(dir + "/whole", sharded);
    // These tiles are unquantized (32-bit indices on the leaves): the validator passes them too.
    if (std::system("command -v node > /dev/null 2>&1") == 0) {
        std::string command = "'" + repoDir() + "/scripts/validate_gltf.sh'", output;
        for (const std::string& f : test::filesUnder(sharded))
            if (f.size() > 4 && f.substr(f.size() - 4) == ".glb") command += " '" + sharded + "/" + f + "'";
        EXPECT_EQ(runScript(command, &output), 0) << output;
    }
}

TEST_F(BakeCli, BadInputExitsTwoAndLeavesNothing) {
    const std::string dir = test::scratchDir("bake_cli_bad");
    const std::string project = writeProject(dir);
    struct Case {
        std::string args, expect;
    };
    std::ofstream(dir + "/blocker") << "a file, not a folder";
    const std::vector<Case> cases = {
        {"--shard 5/4", "5/4"},
        {"--shard 0/0", "0/0"},
        {"--shard two", "expected I/N"},
        {"--region 0,0,0,0", "--region"},
        {"--region 10,10,1,300", "--region"},
        {"--levels 9", "levels"},
        {"--tile 1", "tile"},
    };
    for (const Case& c : cases) {
        const test::CliRun r = bake("'" + project + "' -o '" + dir + "/world' " + c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.out;
        EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.args << ": " << r.out;
        EXPECT_FALSE(fs::exists(dir + "/world")) << c.args;
    }
    const test::CliRun unwritable = bake("'" + project + "' -o '" + dir + "/blocker/world' --region 0,0,200,200");
    EXPECT_EQ(unwritable.exit_code, 2) << unwritable.out;
    EXPECT_NE(unwritable.out.find("blocker/world"), std::string::npos) << unwritable.out;
    const test::CliRun no_project = bake("'" + dir + "/missing.tsyn' -o '" + dir + "/world'");
    EXPECT_EQ(no_project.exit_code, 2) << no_project.out;
    EXPECT_FALSE(fs::exists(dir + "/world"));

    // A merge naming a missing tile writes no tileset.json; a bake into another bake's folder is refused.
    const std::string world = dir + "/small";
    const test::CliRun small = bake("'" + project + "' -o '" + world + "' --region 0,0,200,200 --tile 64 --levels 2");
    ASSERT_EQ(small.exit_code, 0) << small.out;
    fs::remove(world + "/tileset.json");
    ASSERT_TRUE(fs::remove(world + "/tiles/2/1/2.glb"));
    const test::CliRun merge = test::runTerrasynth("bake --merge '" + world + "'");
    EXPECT_EQ(merge.exit_code, 2) << merge.out;
    EXPECT_NE(merge.out.find("tiles/2/1/2.glb"), std::string::npos) << merge.out;
    EXPECT_FALSE(fs::exists(world + "/tileset.json"));
    const test::CliRun other = bake("'" + project + "' -o '" + world + "' --region 0,0,200,200 --tile 32 --levels 2");
    EXPECT_EQ(other.exit_code, 2) << other.out;
    EXPECT_NE(other.out.find("tile_size"), std::string::npos) << other.out;
    const test::CliRun not_a_bake = test::runTerrasynth("bake --merge '" + dir + "'");
    EXPECT_EQ(not_a_bake.exit_code, 2) << not_a_bake.out;
}

TEST_F(BakeCli, DeepTreeGetsImplicitTilingThatTheClientExpands) {
    // 8-quad tiles over 300^2 samples: 7 levels of tree, so auto picks implicit tiling with two
    // levels of subtree files, which the client must follow to find every tile.
    const std::string dir = test::scratchDir("bake_cli_implicit");
    const std::string project = writeProject(dir), world = dir + "/world";
    const test::CliRun r = bake("'" + project + "' -o '" + world + "' --region 0,0,300,300 --tile 8 --levels 3");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("implicit tiling"), std::string::npos) << r.out;
    int subtrees = 0, glbs = 0;
    for (const std::string& f : test::filesUnder(world)) {
        subtrees += f.find(".subtree") != std::string::npos;
        glbs += f.find(".glb") != std::string::npos;
    }
    EXPECT_GT(subtrees, 1);
    if (std::system("command -v node > /dev/null 2>&1") != 0) GTEST_SKIP() << "node is not installed";
    std::string output;
    EXPECT_EQ(runScript("node '" + repoDir() + "/scripts/check_tileset.mjs' '" + world + "'", &output), 0) << output;
    EXPECT_NE(output.find("implicit tileset"), std::string::npos) << output;
    EXPECT_NE(output.find(std::to_string(glbs) + " contents loaded"), std::string::npos) << output;
}
