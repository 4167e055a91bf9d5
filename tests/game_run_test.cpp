// The game binary end to end (build/bin/terrasynth_game), in a window under xvfb-run (Mesa
// llvmpipe), with the shipped project: a 20 km terrain-following flight, determinism, a start
// 10^6 pixels from the origin, a clean exit while workers are busy, and bad input refused before
// any window opens. Tests that need a window skip only when there is neither DISPLAY nor xvfb-run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using terrasynth::test::CliRun;

std::string game() { return terrasynth::test::binDir() + "/terrasynth_game"; }

bool canShowWindows() {
    const char* display = std::getenv("DISPLAY");
    return (display && *display) || terrasynth::test::haveProgram("xvfb-run");
}

// Runs the game in a window (under xvfb-run when there is no DISPLAY).
CliRun runInWindow(const std::string& args) {
    return terrasynth::test::runCommand(terrasynth::test::xvfbPrefix() + "'" + game() + "' " + args);
}

json readJson(const std::string& path) {
    std::ifstream in(path);
    json j;
    if (!in) {
        ADD_FAILURE() << "no stats written at " << path;
        return j;
    }
    in >> j;
    return j;
}

std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// --- bad input: exit 2 with the reason, before any window (no display is offered at all: a
// window attempt would fail with GLFW's message instead of the expected one) -------------------

void expectRefused(const std::string& args, const std::string& expected, const std::string& env = "") {
    const CliRun r = terrasynth::test::runCommand("env -u DISPLAY " + env + " '" + game() + "' " + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out;
    EXPECT_NE(r.out.find(expected), std::string::npos) << args << ": expected \"" << expected << "\" in\n" << r.out;
    EXPECT_EQ(r.out.find("window"), std::string::npos) << args << ": tried to open a window\n" << r.out;
}

TEST(GameBadInput, RefusedBeforeAnyWindowWithExitCodeTwo) {
    const std::string dir = terrasynth::test::scratchDir("game_bad_input");
    expectRefused("--bogus", "--bogus");
    expectRefused("--size 10x10", "--size 10x10");
    expectRefused("--start 12", "--start 12");
    // NaN and infinity: --autopilot nan, --heading nan and --start 1e300,0 hung, --fixed-dt nan was
    // silently ignored.
    for (const char* flag : {"--autopilot", "--heading", "--fixed-dt", "--seed", "--check-holes"})
        for (const char* value : {"nan", "inf"}) expectRefused(std::string(flag) + " " + value, std::string(flag) + ": expected a finite number in [");
    expectRefused("--start 1e300,0", "--start");
    expectRefused("--start nan,0", "--start");
    expectRefused("--project " + dir + "/missing.tsyn", dir + "/missing.tsyn");
    // An invalid project: the loader's message names the file and the field.
    std::ofstream(dir + "/bad.tsyn") << R"({"format": "terrasynth-project", "version": 1, "exemplars": ["ex"], "size": [-5, 3]})";
    expectRefused("--project " + dir + "/bad.tsyn", "bad.tsyn: size");
    // A database that would have to be rebuilt from an unreadable exemplar.
    fs::create_directories(dir + "/ex");
    fs::copy_file(terrasynth::test::dataDir() + "/exemplars/orom_alaska.json", dir + "/ex/broken.json");
    std::ofstream(dir + "/ex/broken.png") << "not a png";
    std::ofstream(dir + "/corrupt.tsyn") << R"({"format": "terrasynth-project", "version": 1, "exemplars": ["ex"]})";
    expectRefused("--project " + dir + "/corrupt.tsyn", "broken.png");
    // Unwritable outputs.
    std::ofstream(dir + "/a_file") << "x";
    expectRefused("--screenshot-every 5 --out " + dir + "/a_file", "--out");
    expectRefused("--screenshot-every 5", "--screenshot-every needs --out");
    expectRefused("--stats " + dir + "/a_file/folder/stats.json", "--stats: " + dir + "/a_file/folder/stats.json: " + dir +
                                                                     "/a_file is a file, not a folder");
    expectRefused("--terrain-options tileSize=7", "tileSize");
    // No OpenCL device: the loader finds no platform; the message suggests the reference backend.
    fs::create_directories(dir + "/no_icd");
    expectRefused("", "--backend reference", "OCL_ICD_VENDORS='" + dir + "/no_icd'");
    // Help is not an error.
    EXPECT_EQ(terrasynth::test::runCommand("'" + game() + "' --help").exit_code, 0);
}

// --- flights -----------------------------------------------------------------------------------

TEST(GameFlight, AutopilotTwentyKilometresAboveTheExactGroundWithoutHoles) {
    if (!canShowWindows()) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    const std::string dir = terrasynth::test::scratchDir("game_autopilot");
    // 20 km at 300 m/s: 67 simulated seconds in steps of 0.1 s.
    const CliRun r = runInWindow("--seed 42 --autopilot 67 --fixed-dt 0.1 --size 640x360 --check-holes 10 --stats " +
                                 dir + "/stats.json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const json s = readJson(dir + "/stats.json");
    const json& f = s["flight"];
    std::printf("flight: %.1f km, above ground %.1f .. %.1f m, %d rings, %d hole frames of %d checked\n",
                f["distance_km"].get<double>(), f["min_above_ground_m"].get<double>(),
                f["max_above_ground_m"].get<double>(), f["rings_collected"].get<int>(),
                s["holes"]["frames_with_holes"].get<int>(), s["holes"]["frames_checked"].get<int>());
    EXPECT_GE(f["distance_km"].get<double>(), 20.0);
    EXPECT_EQ(f["below_ground_steps"].get<int>(), 0);
    EXPECT_EQ(f["crashes"].get<int>(), 0);
    // 300 +- 100 m but across an escarpment steeper than the aircraft's vertical limits can follow
    // (game_flight_test.cpp, GameAutopilot).
    EXPECT_GT(f["min_above_ground_m"].get<double>(), 150.0);
    EXPECT_LT(f["max_above_ground_m"].get<double>(), 450.0);
    // The log holds every step; the aircraft is above the exact ground in each, and within the band
    // in nearly all.
    const json& log = s["log"];
    ASSERT_EQ(log.size(), f["steps"].get<size_t>());
    size_t in_band = 0;
    for (const json& row : log) {
        EXPECT_GT(row[3].get<double>(), row[4].get<double>());
        const double agl = row[3].get<double>() - row[4].get<double>();
        in_band += agl > 200.0 && agl < 400.0;
    }
    std::printf("%.1f%% of the steps within 300 +- 100 m above the ground\n", 100.0 * in_band / log.size());
    EXPECT_GE(in_band, 0.95 * log.size());
    // No hole pixels in any checked frame (the plugin_render_test criterion), and the check looked.
    EXPECT_GT(s["holes"]["frames_checked"].get<int>(), 20);
    EXPECT_GT(s["holes"]["required_pixels"].get<long long>(), 0);
    EXPECT_EQ(s["holes"]["hole_pixels"].get<long long>(), 0);
    // TerrainNode::heightAt agrees with the exact ground on full-resolution tiles.
    EXPECT_GT(s["height_at_level0"]["samples"].get<int>(), 100);
    EXPECT_LE(s["height_at_level0"]["max_error_m"].get<double>(), 0.01);
    EXPECT_EQ(s["tiles"]["build_failures"].get<int>(), 0);
    EXPECT_GT(s["triangles"]["median"].get<double>(), 0.0);
    EXPECT_TRUE(s["clean_exit"].get<bool>());
}

TEST(GameFlight, SameSeedSameFlightAndPicturesAnotherSeedDiffers) {
    if (!canShowWindows()) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    const std::string dir = terrasynth::test::scratchDir("game_determinism");
    auto fly = [&](const std::string& name, int seed) {
        fs::create_directories(dir + "/" + name);
        const CliRun r = runInWindow("--seed " + std::to_string(seed) +
                                     " --autopilot 5 --fixed-dt 0.1 --size 480x270 --screenshot-every 25 --out " +
                                     dir + "/" + name + " --stats " + dir + "/" + name + "/stats.json");
        EXPECT_EQ(r.exit_code, 0) << r.out;
        return readJson(dir + "/" + name + "/stats.json");
    };
    const json a = fly("a", 42), b = fly("b", 42), c = fly("c", 7);
    ASSERT_FALSE(a["log"].empty());
    EXPECT_EQ(a["log"], b["log"]) << "same seed and script, different per-step heights";
    EXPECT_NE(a["log"], c["log"]) << "another seed flew over the same ground";
    // Screenshots of the settled view at the same steps: identical bytes.
    int compared = 0;
    for (const auto& entry : fs::directory_iterator(dir + "/a")) {
        if (entry.path().extension() != ".png") continue;
        const std::string other = dir + "/b/" + entry.path().filename().string();
        ASSERT_TRUE(fs::exists(other)) << other;
        EXPECT_EQ(fileBytes(entry.path().string()), fileBytes(other)) << entry.path().filename();
        ++compared;
    }
    EXPECT_GE(compared, 2);
    EXPECT_NE(fileBytes(dir + "/a/step_000025.png"), fileBytes(dir + "/c/step_000025.png"));
}

TEST(GameFlight, FarFromTheOriginTilesAreSeamlessAndHeightsExact) {
    if (!canShowWindows()) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    const std::string dir = terrasynth::test::scratchDir("game_far_start");
    // 10^6 level-0 pixels east and south of the origin: 92,600 km at 92.6 m per pixel.
    const CliRun r = runInWindow("--seed 42 --start 92600,-92600 --autopilot 6 --fixed-dt 0.1 --size 480x270 "
                                 "--check-holes 5 --stats " + dir + "/stats.json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const json s = readJson(dir + "/stats.json");
    const json& first = s["log"].front();
    EXPECT_NEAR(first[1].get<double>(), 92600000.0, 1000.0);
    EXPECT_NEAR(first[2].get<double>(), -92600000.0, 1000.0);
    EXPECT_EQ(s["flight"]["below_ground_steps"].get<int>(), 0);
    EXPECT_GT(s["holes"]["frames_checked"].get<int>(), 5);
    EXPECT_EQ(s["holes"]["hole_pixels"].get<long long>(), 0);
    EXPECT_GT(s["height_at_level0"]["samples"].get<int>(), 20);
    EXPECT_LE(s["height_at_level0"]["max_error_m"].get<double>(), 0.01);
    EXPECT_EQ(s["tiles"]["build_failures"].get<int>(), 0);
}

TEST(GameStart, BuildsAMissingDatabaseCacheInTheWindow) {
    if (!canShowWindows()) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    const std::string dir = terrasynth::test::scratchDir("game_first_start");
    std::ofstream(dir + "/world.tsyn") << R"({"format": "terrasynth-project", "version": 1, "exemplars": [")" +
                                              terrasynth::test::dataDir() + R"(/exemplars"], "size": [256, 256]})";
    ASSERT_FALSE(fs::exists(dir + "/world.tsdb"));
    const CliRun r = runInWindow("--project " + dir + "/world.tsyn --autopilot 1 --fixed-dt 0.1 --size 480x270 --stats " +
                                 dir + "/stats.json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_TRUE(fs::exists(dir + "/world.tsdb")) << "the database cache was not written";
    const json s = readJson(dir + "/stats.json");
    EXPECT_GT(s["terrain_ready_s"].get<double>(), 0.0);
    EXPECT_GT(s["flight"]["steps"].get<int>(), 0);
}

TEST(GameExit, ClosingWhileWorkersAreBusyJoinsThemAndExitsZero) {
    if (!canShowWindows()) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    const std::string dir = terrasynth::test::scratchDir("game_exit");
    // A close request (SIGTERM takes the same path as the window's close button) a few seconds in,
    // while tiles, ground blocks and rings are being synthesized.
    const std::string script = "'" + game() + "' --seed 42 --stats '" + dir +
                               "/stats.json' & pid=\\$!; sleep 6; kill -TERM \\$pid; wait \\$pid; echo exit=\\$?";
    const CliRun r = terrasynth::test::runCommand(terrasynth::test::xvfbPrefix() + "sh -c \"" + script + "\"");
    EXPECT_NE(r.out.find("exit=0"), std::string::npos) << r.out;
    const json s = readJson(dir + "/stats.json");
    EXPECT_TRUE(s.value("clean_exit", false));
}

TEST(GameSoak, FourMinutesOverNewGroundMemoryPlateausAndCachesStayWithinTheirCaps) {
    // scripts/soak_game.sh 240 (label `soak`): resident memory at the end within 10% of its value
    // at a fifth of the flight, the tile and ground caches within their caps; frame times are the
    // script's full run's to judge (SOAK_CHECK_FRAMES=0: no speed in tests).
    if (!canShowWindows()) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    const std::string dir = terrasynth::test::scratchDir("game_soak");
    const std::string repo = terrasynth::test::dataDir() + "/..";
    const std::string build = fs::path(terrasynth::test::binDir()).parent_path().string();
    const CliRun r = terrasynth::test::runCommand("cd '" + repo + "' && OUT='" + dir +
                                                  "' SOAK_CHECK_FRAMES=0 bash scripts/soak_game.sh 240 '" + build + "'");
    std::printf("%s\n", r.out.c_str());
    EXPECT_EQ(r.exit_code, 0) << r.out;
    const json soak = readJson(dir + "/soak.json");
    ASSERT_TRUE(soak.contains("checks")) << r.out;
    for (const auto& [name, ok] : soak["checks"].items()) EXPECT_TRUE(ok.get<bool>()) << name;
    EXPECT_GE(soak["game_series"].size(), 20u);  // a sample every 10 s
    EXPECT_GT(soak["distance_km"].get<double>(), 30.0);  // new ground all the way
    EXPECT_EQ(soak["tiles"]["build_failures"].get<int>(), 0);
}

}  // namespace
