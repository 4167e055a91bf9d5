// The editor's window-free parts: the --script parser, the command line and autosave names, and the
// sketching geometry (over-sketching, junctions, lassos).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "terrasynth_editor/editor_options.h"
#include "terrasynth_editor/script.h"
#include "terrasynth_editor/sketch_geometry.h"
#include "test_support.h"

namespace terrasynth::editor {
namespace {

TEST(EditorScript, ParsesEveryCommandAndNamesTheLineOfAnError) {
    const std::string text =
        "# a comment\n"
        "settle\n"
        "view aerial 512 512 60000   # trailing comment\n"
        "view free 512 512 9000 30 40\n"
        "tool point\n"
        "set paint.type extreme alpine\n"
        "move 640 360\n"
        "click\n"
        "drag 640 360 690 360 12\n"
        "item base.low 10 0\n"
        "key ctrl+shift+z\n"
        "screenshot out.png 3d\n"
        "save\n"
        "heights h.f32\n"
        "undo-all\n"
        "wait-autosave\n"
        "expect-error radius must\n"
        "phase point_drag\n"
        "echo hello world\n"
        "wait 3\n"
        "quit\n";
    auto parsed = parseScript(text, "t.script");
    ASSERT_TRUE(parsed) << parsed.message();
    const auto& c = *parsed;
    ASSERT_EQ(c.size(), 20u);
    EXPECT_EQ(c[0].op, "settle");
    EXPECT_EQ(c[0].line, 2);
    EXPECT_EQ(c[1].numbers, (std::vector<double>{512, 512, 60000}));
    EXPECT_EQ(c[2].numbers.size(), 5u);
    EXPECT_EQ(c[7].numbers, (std::vector<double>{640, 360, 690, 360, 12}));
    EXPECT_EQ(c[8].args[0], "base.low");
    EXPECT_EQ(c[8].numbers, (std::vector<double>{10, 0}));
    EXPECT_EQ(c[4].args, (std::vector<std::string>{"paint.type", "extreme alpine"}));
    EXPECT_EQ(c[15].args[0], "radius must");
    EXPECT_EQ(c[17].args[0], "hello world");

    struct Bad {
        const char* text;
        const char* message;
    };
    for (const Bad& b : {Bad{"wait 1\nfly 3\n", "t.script:2: unknown command 'fly'"},
                         Bad{"drag 1 2 3\n", "t.script:1: drag: needs X0 Y0 X1 Y1 [STEPS]"},
                         Bad{"move 1 x\n", "t.script:1: move: 'x' is not a number"},
                         Bad{"view aerial 1 2\n", "t.script:1: view: needs"},
                         Bad{"view aerial 1 2 0\n", "must be > 0"},
                         Bad{"press thumb\n", "unknown button 'thumb'"},
                         Bad{"key ctrl+banana\n", "unknown key 'ctrl+banana'"},
                         Bad{"screenshot a.png both\n", "ui or 3d"},
                         Bad{"wait -1\n", "must not be negative"},
                         Bad{"expect-error\n", "needs TEXT"}}) {
        auto r = parseScript(b.text, "t.script");
        ASSERT_FALSE(r) << b.text;
        EXPECT_NE(r.message().find(b.message), std::string::npos) << r.message();
    }
    auto missing = readScript(test::scratchDir("editor_script") + "/none.script");
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.message().find("none.script"), std::string::npos);
}

TEST(EditorScript, KeySpecs) {
    int key = 0, mods = 0;
    ASSERT_TRUE(parseKeySpec("ctrl+shift+z", &key, &mods));
    EXPECT_EQ(key, GLFW_KEY_Z);
    EXPECT_EQ(mods, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT);
    ASSERT_TRUE(parseKeySpec("Delete", &key, &mods));
    EXPECT_EQ(key, GLFW_KEY_DELETE);
    EXPECT_EQ(mods, 0);
    ASSERT_TRUE(parseKeySpec("f5", &key, &mods));
    EXPECT_EQ(key, GLFW_KEY_F5);
    EXPECT_FALSE(parseKeySpec("hyper+a", &key, &mods));
    EXPECT_FALSE(parseKeySpec("f13", &key, &mods));
}

TEST(EditorOptions, CommandLineAndAutosave) {
    const char* good[] = {"terrasynth_editor", "w.tsyn", "--size", "640x360", "--stats", "s.json", "--recover",
                          "--clear-color", "1,0,1", "--backend", "reference"};
    auto o = parseEditorOptions(11, good);
    ASSERT_TRUE(o) << o.message();
    EXPECT_EQ(o->project, "w.tsyn");
    EXPECT_EQ(o->width, 640);
    EXPECT_EQ(o->height, 360);
    EXPECT_TRUE(o->recover);
    EXPECT_EQ(o->clear_color[1], 0.0f);
    EXPECT_EQ(o->synthesizer.backend, SynthesisBackend::Reference);
    const char* bad_size[] = {"e", "w.tsyn", "--size", "64x36"};
    EXPECT_NE(parseEditorOptions(4, bad_size).message().find("--size"), std::string::npos);
    const char* bad_colour[] = {"e", "w.tsyn", "--clear-color", "1,2,0"};
    EXPECT_NE(parseEditorOptions(4, bad_colour).message().find("--clear-color"), std::string::npos);
    const char* none[] = {"e"};
    EXPECT_FALSE(parseEditorOptions(1, none));
    // NaN reached an ImGui assertion (--ui-scale nan aborted the editor): every number is checked
    // for a finite value in range, the flag named.
    for (const char* flag : {"--ui-scale", "--drag-preview-levels"})
        for (const char* value : {"nan", "inf", "-inf"}) {
            const char* argv[] = {"e", "w.tsyn", flag, value};
            const auto refused = parseEditorOptions(4, argv);
            ASSERT_FALSE(refused) << flag << " " << value;
            EXPECT_NE(refused.message().find(flag), std::string::npos) << refused.message();
            EXPECT_NE(refused.message().find("expected a finite number in ["), std::string::npos) << refused.message();
        }
    const char* infinite_skirt[] = {"e", "w.tsyn", "--terrain-options", "skirt=inf"};
    EXPECT_NE(parseEditorOptions(4, infinite_skirt).message().find("skirt"), std::string::npos);
    // --stats is written at exit, so an unwritable one is refused up front (as the game does).
    // Missing folders are made at exit; a file where a folder should be cannot be.
    const std::string stats_dir = test::scratchDir("editor_stats_target");
    std::ofstream(stats_dir + "/in_the_way") << "a file";
    const std::string unwritable = stats_dir + "/in_the_way/stats.json";
    const char* bad_stats[] = {"e", "w.tsyn", "--stats", unwritable.c_str()};
    const auto stats = parseEditorOptions(4, bad_stats);
    ASSERT_FALSE(stats);
    EXPECT_NE(stats.message().find("--stats"), std::string::npos) << stats.message();

    EXPECT_EQ(terrainPixelError("llvmpipe (LLVM 15.0.6, 256 bits)"), 12.0f);
    EXPECT_EQ(terrainPixelError("NVIDIA GeForce RTX 3060/PCIe/SSE2"), 6.0f);
    const char* bad_terrain[] = {"e", "w.tsyn", "--terrain-options", "tileSize=7"};
    EXPECT_NE(parseEditorOptions(4, bad_terrain).message().find("tileSize"), std::string::npos);

    EXPECT_EQ(autosavePath("/a/b/world.tsyn"), "/a/b/world.autosave.tsyn");
    const std::string dir = test::scratchDir("editor_autosave_name");
    const std::string project = dir + "/w.tsyn";
    std::ofstream(project) << "{}";
    EXPECT_EQ(newerAutosave(project), "");
    std::ofstream(autosavePath(project)) << "{}";
    // Make the autosave clearly newer than the project.
    std::filesystem::last_write_time(project, std::filesystem::last_write_time(autosavePath(project)) - std::chrono::seconds(5));
    EXPECT_EQ(newerAutosave(project), autosavePath(project));
    std::filesystem::last_write_time(project, std::filesystem::last_write_time(autosavePath(project)) + std::chrono::seconds(5));
    EXPECT_EQ(newerAutosave(project), "");
}

TEST(EditorSketch, DecimateLengthAndArcLength) {
    Polyline line;
    for (int i = 0; i <= 100; ++i) line.push_back({i * 0.5, 0.0});
    const Polyline d = decimate(line, 5.0);
    EXPECT_EQ(d.front(), line.front());
    EXPECT_EQ(d.back(), line.back());
    EXPECT_EQ(d.size(), 11u);
    EXPECT_DOUBLE_EQ(polylineLength(line), 50.0);
    const Polyline l = {{0, 0}, {10, 0}, {10, 10}};
    EXPECT_EQ(pointAtFraction(l, 0.75), std::make_pair(10.0, 5.0));
    const Nearest n = nearestOnPolyline(l, 12, 5);
    EXPECT_DOUBLE_EQ(n.t, 0.75);
    EXPECT_DOUBLE_EQ(n.distance, 2.0);
    EXPECT_EQ(n.segment, 1);
}

TEST(EditorSketch, OverSketchReplacesTheSpanBetweenTheStrokesEnds) {
    const Polyline course = {{0, 0}, {10, 0}, {20, 0}, {30, 0}, {40, 0}};
    // A detour from x=12 to x=28 north of the course.
    const Polyline stroke = {{12, 1}, {20, -8}, {28, 1}};
    const Polyline out = overSketch(course, stroke);
    const Polyline expected = {{0, 0}, {10, 0}, {12, 1}, {20, -8}, {28, 1}, {30, 0}, {40, 0}};
    EXPECT_EQ(out, expected);
    // Drawn against the course's direction: the same result.
    Polyline reversed(stroke.rbegin(), stroke.rend());
    EXPECT_EQ(overSketch(course, reversed), expected);
    // Starting near the end and running past it extends the course.
    const Polyline extended = overSketch(course, {{39, 0}, {50, 5}, {60, 5}});
    EXPECT_EQ(extended.front(), std::make_pair(0.0, 0.0));
    EXPECT_EQ(extended.back(), std::make_pair(60.0, 5.0));
}

TEST(EditorSketch, JunctionsLassosAndCentroids) {
    const Polyline a = {{0, 0}, {10, 10}}, b = {{0, 10}, {10, 0}};
    const auto x = crossings(a, b);
    ASSERT_EQ(x.size(), 1u);
    EXPECT_NEAR(x[0].first, 5.0, 1e-12);
    EXPECT_NEAR(x[0].second, 5.0, 1e-12);
    EXPECT_TRUE(crossings(a, {{20, 20}, {30, 20}}).empty());
    const Polyline loop = {{0, 0}, {10, 0}, {10, 10}, {5, -5}};
    EXPECT_EQ(selfCrossings(loop).size(), 1u);
    const Polyline square = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    EXPECT_EQ(centroid(square), std::make_pair(5.0, 5.0));
    EXPECT_TRUE(insidePolygon(square, 5, 5));
    EXPECT_FALSE(insidePolygon(square, 11, 5));
    EXPECT_FALSE(insidePolygon({{0, 0}, {1, 1}}, 0.5, 0.5));
}

}  // namespace
}  // namespace terrasynth::editor
