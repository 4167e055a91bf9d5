// The editor program (build/bin/terrasynth_editor) in a real window under Xvfb (Mesa llvmpipe),
// driven by --script files the way a designer would: points added and dragged in the 3D view, a
// curve, a type stroke, a freeze, a paste and a layer peak saved and reopened bit for bit, undo back
// to the start, the panels and the terrain on screen, the flatten brush pulling the heights under it
// toward their mean, the autosave after kill -9, the latency targets from --stats (with a generous
// factor: CI shares two cores), and bad input refused before any window opens. When DISPLAY is
// unset each test re-runs itself under xvfb-run.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <osg/Image>
#include <osgDB/ReadFile>

#include "terrasynth/edit_session.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/layers.h"
#include "terrasynth/terrain.h"
#include "test_support.h"

namespace terrasynth {
namespace {

constexpr int kW = 1280, kH = 720;
constexpr double kAerialWidthM = 60000.0;  // what kAerialStart shows
// How the scripts start: the session open and the view filled in, then straight down on the middle of
// the extent, 60 km across.
constexpr const char* kAerialStart = "settle\nview aerial 512 512 60000\nsettle\n";
// The latency targets (issue 14) and the factor the test allows on a shared CI machine.
constexpr double kSlack = 3.0;

std::string editorBin() { return test::binDir() + "/terrasynth_editor"; }

struct EditorRun {
    int code = -1;
    std::string out;
};

EditorRun runEditor(const std::string& args, const std::string& env = "") {
    const std::string cmd = env + " timeout 900 '" + editorBin() + "' " + args + " 2>&1";
    EditorRun r;
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buffer[4096];
    while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) r.out.append(buffer, n);
    const int status = ::pclose(pipe);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// The default 1024^2 project on the tests' shared database.
std::string writeProject(const std::string& dir, const std::string& constraints = "{}") {
    if (!test::defaultDatabase()) return "";
    Project p;
    p.database = test::defaultDatabasePath();
    p.constraints_json = constraints;
    const std::string path = dir + "/p.tsyn";
    EXPECT_TRUE(saveProject(p, path));
    return path;
}

std::string writeText(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
    return path;
}

Heightfield readF32(const std::string& path) {
    auto e = readExemplar(path);
    EXPECT_TRUE(e) << e.message();
    return e ? e->field : Heightfield();
}

Heightfield extentHeights(const std::string& project) {
    auto terrain = Terrain::open(project);
    EXPECT_TRUE(terrain) << terrain.message();
    if (!terrain) return {};
    EXPECT_TRUE(terrain.value()->usesEditedHeights()) << project << " was not read from its sidecar";
    auto h = terrain.value()->heights(terrain.value()->extent(), 0);
    EXPECT_TRUE(h) << h.message();
    return h ? *h : Heightfield();
}

// Window pixel (x, y from the top) of a screenshot.
osg::Vec3i pixel(const osg::Image& image, int x, int y) {
    const unsigned char* p = image.data(x, image.t() - 1 - y);
    return {p[0], p[1], p[2]};
}

bool magenta(const osg::Vec3i& p) { return p.x() > 235 && p.y() < 25 && p.z() > 235; }

// "terrasynth_editor: <label>: changed X Y W H" lines of a scripted run.
std::optional<PixelWindow> changedWindow(const std::string& out, const std::string& label) {
    std::istringstream lines(out);
    const std::string key = "terrasynth_editor: " + label + ": changed ";
    for (std::string line; std::getline(lines, line);) {
        const size_t at = line.find(key);
        if (at == std::string::npos) continue;
        std::istringstream in(line.substr(at + key.size()));
        PixelWindow w;
        in >> w.x >> w.y >> w.width >> w.height;
        return w;
    }
    return std::nullopt;
}

#define RUN_UNDER_XVFB(name)                                                                       \
    do {                                                                                           \
        const int rc = test::rerunUnderXvfbUnlessDisplay(name);                                    \
        if (rc == test::kNoXvfb) GTEST_SKIP() << "no DISPLAY and no xvfb-run";                     \
        if (rc != test::kHaveDisplay) {                                                            \
            ASSERT_EQ(rc, 0) << "the editor test under xvfb-run failed (its output is above)";      \
            return;                                                                                \
        }                                                                                          \
    } while (0)

TEST(EditorGui, BadInputExitsTwoBeforeAnyWindow) {
    // No display at all: a window would fail with exit 1, so exit 2 proves none was attempted.
    const std::string dir = test::scratchDir("editor_bad_input");
    ASSERT_FALSE(writeProject(dir).empty());
    const std::string bad_json = writeText(dir + "/bad.tsyn", R"({"format": "terrasynth-project", "version": 1,
        "database": ")" + test::defaultDatabasePath() + R"(", "size": [256, 256],
        "synthesis": {"seed": 1, "jitter": 5}, "constraints": {}, "layers": []})");
    EditorRun r = runEditor("'" + bad_json + "'", "env -u DISPLAY");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("bad.tsyn"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("synthesis.jitter"), std::string::npos) << r.out;

    // Constraints are checked against the database before the window too.
    const std::string bad_point = writeProject(test::scratchDir("editor_bad_point"),
                                               R"({"points": [{"x": 10, "y": 10, "height_m": 100, "radius_px": 0}]})");
    r = runEditor("'" + bad_point + "'", "env -u DISPLAY");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("constraints.points[0].radius_px"), std::string::npos) << r.out;

    r = runEditor("'" + dir + "/missing.tsyn'", "env -u DISPLAY");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("missing.tsyn"), std::string::npos) << r.out;

    const std::string script = writeText(dir + "/s.script", "settle\nfly away\n");
    r = runEditor("'" + dir + "/p.tsyn' --script '" + script + "'", "env -u DISPLAY");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("s.script:2: unknown command 'fly'"), std::string::npos) << r.out;

    r = runEditor("'" + dir + "/p.tsyn' --size 10x10", "env -u DISPLAY");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("--size"), std::string::npos) << r.out;
}

TEST(EditorGui, PointClickDragSaveAndWhatIsOnScreen) {
    RUN_UNDER_XVFB("EditorGui.PointClickDragSaveAndWhatIsOnScreen");
    const std::string dir = test::scratchDir("editor_point");
    const std::string project = writeProject(dir);
    ASSERT_FALSE(project.empty());
    const std::string script = writeText(dir + "/point.script", std::string(kAerialStart) + R"(screenshot )" + dir + R"(/before.png 3d
screenshot )" + dir + R"(/ui.png ui
tool point
set point.raise 400
move 640 360
click
settle
screenshot )" + dir + R"(/after.png 3d
drag 640 360 690 360 10
settle
screenshot )" + dir + R"(/editor.png ui
save )" + dir + R"(/saved.tsyn
expect-ok
set point.radius 0
move 760 520
click
expect-error point.radius_px
)");
    const EditorRun r = runEditor("'" + project + "' --clear-color 1,0,1 --script '" + script + "'");
    ASSERT_EQ(r.code, 0) << r.out;

    // The saved point: at the picked pixel (the view's centre), then moved by 50 screen pixels.
    auto session = EditSession::open(dir + "/saved.tsyn");
    ASSERT_TRUE(session) << session.message();
    const EditSession& s = **session;
    ASSERT_EQ(s.pointIds().size(), 1u);
    const PointConstraint& p = *s.point(s.pointIds()[0]);
    const double mpp = s.frame().meters_per_pixel;
    const double expected_x = 512.0 + 50.0 * (kAerialWidthM / kW) / mpp;
    EXPECT_NEAR(p.x, expected_x, 1.0);
    EXPECT_NEAR(p.y, 512.0, 1.0);
    // Its height holds in the reopened terrain (the sidecar's heights, lifted onto the target).
    auto terrain = Terrain::open(dir + "/saved.tsyn");
    ASSERT_TRUE(terrain) << terrain.message();
    auto h = terrain.value()->heightAt(s.frame().worldX(p.x), s.frame().worldY(p.y));
    ASSERT_TRUE(h) << h.message();
    const HeightRange range = heightRange(s.heights());
    EXPECT_NEAR(*h, p.height_m, 0.03 * (range.max - range.min)) << "target " << p.height_m;

    osg::ref_ptr<osg::Image> before = osgDB::readImageFile(dir + "/before.png");
    osg::ref_ptr<osg::Image> after = osgDB::readImageFile(dir + "/after.png");
    osg::ref_ptr<osg::Image> ui = osgDB::readImageFile(dir + "/ui.png");
    ASSERT_TRUE(before.valid() && after.valid() && ui.valid());
    ASSERT_EQ(before->s(), kW);
    ASSERT_EQ(before->t(), kH);
    // The panels are drawn (dark ImGui windows over the terrain on the left and the right).
    for (const auto& [x, y] : {std::pair{120, 300}, std::pair{1100, 300}, std::pair{640, 8}}) {
        const osg::Vec3i a = pixel(*ui, x, y), b = pixel(*before, x, y);
        EXPECT_LT(std::max({a.x(), a.y(), a.z()}), 90) << "no panel at " << x << "," << y;
        EXPECT_NE(a, b) << "the panel at " << x << "," << y << " is missing from the screenshot with panels";
    }
    // The terrain never shows the clear colour (magenta here) in the aerial view over the extent.
    int clear_pixels = 0;
    for (const osg::Image* image : {before.get(), after.get()})
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) clear_pixels += magenta(pixel(*image, x, y));
    EXPECT_EQ(clear_pixels, 0);

    // Before/after differences lie inside the changed window as projected on screen (with the
    // parallax of the relief and a few samples of shading and geomorphing around it), and there are
    // many: the tiles swapped in after ImGui had drawn (OSG issue 924) do draw.
    const auto changed = changedWindow(r.out, "add point");
    ASSERT_TRUE(changed.has_value()) << r.out;
    const double screen_per_px = mpp / (kAerialWidthM / kW);
    auto sx = [&](double px) { return 0.5 * kW + (px - 512.0) * screen_per_px; };
    auto sy = [&](double py) { return 0.5 * kH + (py - 512.0) * screen_per_px; };
    const double left = sx(changed->x), right = sx(changed->x + changed->width);
    const double top = sy(changed->y), bottom = sy(changed->y + changed->height);
    int inside = 0, outside = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const osg::Vec3i a = pixel(*before, x, y), b = pixel(*after, x, y);
            const int d = std::max({std::abs(a.x() - b.x()), std::abs(a.y() - b.y()), std::abs(a.z() - b.z())});
            if (d <= 12) continue;
            const double margin = 24.0 + 0.06 * std::hypot(x - 0.5 * kW, y - 0.5 * kH);
            const bool in = x >= left - margin && x <= right + margin && y >= top - margin && y <= bottom + margin;
            (in ? inside : outside)++;
        }
    const double window_area = (right - left) * (bottom - top);
    std::printf("changed window %lld,%lld %dx%d -> screen %.0f..%.0f x %.0f..%.0f: %d pixels differ inside, %d outside\n",
                static_cast<long long>(changed->x), static_cast<long long>(changed->y), changed->width, changed->height, left, right,
                top, bottom, inside, outside);
    EXPECT_EQ(outside, 0);
    EXPECT_GT(inside, 0.05 * window_area) << "the edited tiles are not on screen";
}

TEST(EditorGui, EditsSaveAndReopenBitIdenticalAndUndoAllRestoresTheStart) {
    RUN_UNDER_XVFB("EditorGui.EditsSaveAndReopenBitIdenticalAndUndoAllRestoresTheStart");
    const std::string dir = test::scratchDir("editor_edits");
    const std::string project = writeProject(dir);
    ASSERT_FALSE(project.empty());
    const std::string type = test::defaultDatabase()->type_names.back();
    const std::string script = writeText(dir + "/edits.script", std::string(kAerialStart) + R"(heights )" + dir + R"(/start.f32
tool curve
set curve.preset ridge
drag 420 250 720 300 12
settle
tool paint
set paint.type )" + type + R"(
set brush.radius 24
drag 430 480 640 480 8
settle
tool freeze
set brush.radius 6
drag 420 180 560 180 6
settle
tool paste
move 760 420
press
move 830 420
move 850 480
move 790 500
move 760 425
release
settle
drag 800 455 860 540 6
settle
tool peak
set peak.height 900
move 560 560
click
settle
expect-ok
view free 560 700 42000 10 32
settle
screenshot )" + dir + R"(/editor.png ui
save )" + dir + R"(/saved.tsyn
heights )" + dir + R"(/after.f32
undo-all
settle
heights )" + dir + R"(/undone.f32
expect-ok
)");
    const EditorRun r = runEditor("'" + project + "' --script '" + script + "'");
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* edit : {"add curve", "paint " , "paste", "add peak"})
        EXPECT_NE(r.out.find(std::string("terrasynth_editor: ") + edit), std::string::npos) << edit << "\n" << r.out;

    const Heightfield start = readF32(dir + "/start.f32");
    const Heightfield after = readF32(dir + "/after.f32");
    const Heightfield undone = readF32(dir + "/undone.f32");
    ASSERT_FALSE(start.empty());
    EXPECT_NE(after.heights, start.heights);
    // Saved and reopened: what the editor had, bit for bit (the session's sidecar).
    const Heightfield reopened = extentHeights(dir + "/saved.tsyn");
    EXPECT_EQ(reopened.heights, after.heights);
    auto session = EditSession::open(dir + "/saved.tsyn");
    ASSERT_TRUE(session) << session.message();
    EXPECT_EQ((*session)->heights().heights, after.heights);
    EXPECT_EQ((*session)->curveIds().size(), 1u);
    EXPECT_EQ((*session)->pasteIds().size(), 1u);
    EXPECT_EQ((*session)->layers().layers.size(), 1u);
    EXPECT_FALSE((*session)->constraints().types.empty());
    EXPECT_FALSE((*session)->constraints().freeze.empty());
    // Undo all: bit-identical to the start.
    EXPECT_EQ(undone.heights, start.heights);
}

TEST(EditorGui, LayerToolsPanelsAndExemplarPaste) {
    RUN_UNDER_XVFB("EditorGui.LayerToolsPanelsAndExemplarPaste");
    const std::string dir = test::scratchDir("editor_layers");
    const std::string project = writeProject(dir);
    ASSERT_FALSE(project.empty());
    // Every layer tool of Bradbury et al. 2014 through the 3D view and the panels, and a piece of an
    // exemplar lassoed on its thumbnail and pasted into the terrain (Gain et al. 2015 fig. 8).
    const std::string script = writeText(dir + "/layers.script", std::string(kAerialStart) + R"(tool ridge
set ridge.height 500
drag 450 300 650 340 10
settle
tool noise
set noise.amplitude 80
drag 700 450 800 550 6
settle
tool holefill
drag 480 420 560 480 6
settle
item holefill.pick.2
click
settle
item holefill.done
click
tool layerpaste
drag 350 550 420 600 6
move 600 600
click
settle
item exemplar.0 -20 -20
press
item exemplar.0 20 -20
item exemplar.0 20 20
item exemplar.0 -20 20
item exemplar.0 -20 -18
release
move 420 220
click
settle
item layer.0
click
drag-item layer0.mid 60 0 10
settle
item layer.1.visible
click
settle
item layer.3.merge
click
settle
view free 512 700 30000 0 30
settle
tool perspective
move 540 390
press
move 580 370
move 620 345
move 660 360
move 700 375
move 740 392
release
settle
expect-ok
save )" + dir + R"(/saved.tsyn
heights )" + dir + R"(/after.f32
)");
    const EditorRun r = runEditor("'" + project + "' --script '" + script + "'");
    ASSERT_EQ(r.code, 0) << r.out;
    for (const char* edit : {"add ridge", "add noise", "pick hole fill", "add layer paste", "paste", "layer bands",
                             "hide layer", "add perspective sketch"})
        EXPECT_NE(r.out.find(std::string("terrasynth_editor: ") + edit + ": changed"), std::string::npos) << edit << "\n" << r.out;
    auto session = EditSession::open(dir + "/saved.tsyn");
    ASSERT_TRUE(session) << session.message();
    const EditSession& s = **session;
    // ridge, noise (hidden), hole fill merged with the layer paste, perspective sketch.
    const auto& layers = s.layers().layers;
    ASSERT_EQ(layers.size(), 4u) << describeLayerStack(s.layers());
    EXPECT_TRUE(std::holds_alternative<RidgeParams>(layers[0].tool));
    EXPECT_NE(layers[0].weights.mid, 1.0f) << "the mid band slider of layer 0 was dragged";
    EXPECT_TRUE(std::holds_alternative<NoiseParams>(layers[1].tool));
    EXPECT_FALSE(layers[1].visible);
    const auto* group = std::get_if<GroupParams>(&layers[2].tool);
    ASSERT_NE(group, nullptr);
    ASSERT_EQ(group->children.size(), 2u);
    const auto* fill = std::get_if<HoleFillParams>(&group->children[0].tool);
    ASSERT_NE(fill, nullptr);
    EXPECT_EQ(fill->choices, std::vector<int>{1}) << "the second of the three variants was picked";
    EXPECT_TRUE(std::holds_alternative<PasteParams>(group->children[1].tool));
    const auto* sketch = std::get_if<PerspectiveParams>(&layers[3].tool);
    ASSERT_NE(sketch, nullptr);
    ASSERT_EQ(sketch->strokes.size(), 1u);
    EXPECT_GE(sketch->strokes[0].points.size(), 5u);
    ASSERT_EQ(s.pasteIds().size(), 1u);
    EXPECT_EQ(s.paste(s.pasteIds()[0])->exemplar, 0);
    EXPECT_EQ(s.heights().heights, readF32(dir + "/after.f32").heights);
    EXPECT_EQ(extentHeights(dir + "/saved.tsyn").heights, readF32(dir + "/after.f32").heights);
}

TEST(EditorGui, FlattenPullsTheHeightsUnderTheBrushTowardTheirMean) {
    RUN_UNDER_XVFB("EditorGui.FlattenPullsTheHeightsUnderTheBrushTowardTheirMean");
    const std::string dir = test::scratchDir("editor_flatten");
    const std::string project = writeProject(dir);
    ASSERT_FALSE(project.empty());
    // One click of the flatten brush in the middle of the view (level-0 pixel ~(512, 512)).
    const std::string script = writeText(dir + "/flatten.script", std::string(kAerialStart) + R"(heights )" + dir + R"(/start.f32
tool flatten
set flatten.radius 64
set flatten.strength 0.9
set flatten.falloff 0.5
move 640 360
click
settle
expect-ok
expect-selected-layer 0
heights )" + dir + R"(/after.f32
save )" + dir + R"(/saved.tsyn
)");
    const EditorRun r = runEditor("'" + project + "' --script '" + script + "'");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(changedWindow(r.out, "add flatten").has_value()) << r.out;

    // The layer: a "replace" paste of the terrain below onto itself, a disc of the brush under the click.
    auto session = EditSession::open(dir + "/saved.tsyn");
    ASSERT_TRUE(session) << session.message();
    const auto& layers = (*session)->layers().layers;
    ASSERT_EQ(layers.size(), 1u) << describeLayerStack((*session)->layers());
    const auto* flatten = std::get_if<PasteParams>(&layers[0].tool);
    ASSERT_NE(flatten, nullptr);
    EXPECT_EQ(flatten->blend, PasteBlend::Replace);
    EXPECT_EQ(flatten->dest.width, 128.0);
    EXPECT_NEAR(flatten->dest.x + 64.0, 512.0, 2.0);
    EXPECT_NEAR(flatten->dest.y + 64.0, 512.0, 2.0);

    const Heightfield start = readF32(dir + "/start.f32");
    const Heightfield after = readF32(dir + "/after.f32");
    ASSERT_FALSE(start.empty());
    ASSERT_EQ(after.width, start.width);
    // The target: the start's mean height under the brush, weighted by its falloff.
    const std::vector<float> mask = regionMask(flatten->dest, flatten->feather_px, start.width, start.height);
    double weight = 0.0, target = 0.0;
    for (size_t i = 0; i < mask.size(); ++i) weight += mask[i], target += mask[i] * start.heights[i];
    ASSERT_GT(weight, 0.0);
    target /= weight;
    // Inside the brush's full-strength core the heights moved toward the target and the ground got
    // flatter; beyond four radii nothing moved. (The multi-band blend pulls the coarse bands only
    // partly over a disc this small, whose blurred mask stays below 1, and spreads them smoothly
    // past its edge, as for any paste layer.)
    const double cx = flatten->dest.x + 0.5 * flatten->dest.width, cy = flatten->dest.y + 0.5 * flatten->dest.height;
    const double core_radius = 0.5 * flatten->dest.width - flatten->feather_px;
    double before_dev = 0.0, after_dev = 0.0, before_rough = 0.0, after_rough = 0.0;
    int core = 0, far = 0, far_moved = 0;
    for (int y = 0; y + 1 < start.height; ++y)
        for (int x = 0; x + 1 < start.width; ++x) {
            const double d = std::hypot(x - cx, y - cy);
            const double a = start.at(x, y), b = after.at(x, y);
            if (d < core_radius) {
                ++core;
                before_dev += std::fabs(a - target);
                after_dev += std::fabs(b - target);
                before_rough += std::fabs(start.at(x + 1, y) - a) + std::fabs(start.at(x, y + 1) - a);
                after_rough += std::fabs(after.at(x + 1, y) - b) + std::fabs(after.at(x, y + 1) - b);
            } else if (d > 2.0 * flatten->dest.width) {
                ++far;
                far_moved += std::fabs(b - a) > 0.01;
            }
        }
    std::printf("target %.1f m over %d core pixels: mean deviation %.2f -> %.2f m, roughness %.2f -> %.2f m/px; "
                "%d of %d far pixels moved\n",
                target, core, before_dev / core, after_dev / core, before_rough / core, after_rough / core, far_moved, far);
    ASSERT_GT(core, 0);
    ASSERT_GT(before_dev / core, 1.0) << "the brush landed on flat ground: the test shows nothing";
    EXPECT_LT(after_dev, 0.5 * before_dev);
    EXPECT_LT(after_rough, 0.5 * before_rough);
    EXPECT_EQ(far_moved, 0);
}

TEST(EditorGui, TheAutosaveHoldsTheLastEditAfterKillAndIsRecovered) {
    RUN_UNDER_XVFB("EditorGui.TheAutosaveHoldsTheLastEditAfterKillAndIsRecovered");
    const std::string dir = test::scratchDir("editor_autosave");
    const std::string project = writeProject(dir);
    ASSERT_FALSE(project.empty());
    const std::string script = writeText(dir + "/kill.script", std::string(kAerialStart) + R"(tool point
move 600 400
click
settle
tool peak
move 700 300
click
settle
wait-autosave
heights )" + dir + R"(/last.f32
echo READY
sleep 600000
)");
    const std::string log = dir + "/editor.log";
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, 1);
        ::dup2(fd, 2);
        const std::string bin = editorBin();
        ::execl(bin.c_str(), bin.c_str(), project.c_str(), "--script", script.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::string out;
    bool ready = false;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(600);
    while (!ready && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        std::ifstream in(log);
        out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        ready = out.find("READY") != std::string::npos;
        int status = 0;
        if (!ready && ::waitpid(pid, &status, WNOHANG) == pid) break;  // it ended early
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    ASSERT_TRUE(ready) << out;
    EXPECT_NE(out.find("autosaved"), std::string::npos) << out;

    // The autosave holds the last completed edit, bit for bit.
    const std::string autosave = dir + "/p.autosave.tsyn";
    const Heightfield last = readF32(dir + "/last.f32");
    EXPECT_EQ(extentHeights(autosave).heights, last.heights);
    auto session = EditSession::open(autosave);
    ASSERT_TRUE(session) << session.message();
    EXPECT_EQ((*session)->pointIds().size(), 1u);
    EXPECT_EQ((*session)->layers().layers.size(), 1u);

    // --recover opens it (it is newer than the project); without --recover a script opens the project.
    const std::string read_back = writeText(dir + "/recover.script", "heights " + dir + "/recovered.f32\n");
    EditorRun r = runEditor("'" + project + "' --recover --script '" + read_back + "'");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("recovering"), std::string::npos) << r.out;
    EXPECT_EQ(readF32(dir + "/recovered.f32").heights, last.heights);
    r = runEditor("'" + project + "' --script '" + read_back + "'");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("--recover"), std::string::npos) << r.out;
    EXPECT_NE(readF32(dir + "/recovered.f32").heights, last.heights);
}

TEST(EditorGui, LatencyTargetsFromStats) {
    RUN_UNDER_XVFB("EditorGui.LatencyTargetsFromStats");
    const std::string dir = test::scratchDir("editor_latency");
    const std::string project = writeProject(dir);
    ASSERT_FALSE(project.empty());
    const std::string script = test::dataDir() + "/../editor_ui/scripts/latency.script";
    const EditorRun r = runEditor("'" + project + "' --script '" + script + "' --stats '" + dir + "/stats.json'");
    ASSERT_EQ(r.code, 0) << r.out;
    std::ifstream in(dir + "/stats.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    std::printf("%s\n", j.dump(1).c_str());
    EXPECT_EQ(j["window"], nlohmann::json({kW, kH}));
    EXPECT_EQ(j["extent"], nlohmann::json({1024, 1024}));
    const auto& lat = j["latency"];
    // How much slower this machine is right now than the quiet 2-core machine the targets are for,
    // measured in the same run by the session's own point-drag edit (runtime code the editor does not
    // change; a previewed step) against session_bench's median for it there
    // (BM_PointDragStepPreview, 14 ms, README). CI shares its two cores with the other tests; a
    // regression in the editor's own part still shows against this.
    const double load = std::max(1.0, lat["point_drag"]["edit_ms"]["median"].get<double>() / 14.0);
    std::printf("machine load factor %.2f\n", load);
    auto check = [&](const char* kind, double median_ms, double p95_ms, int min_count) {
        const auto& s = lat[kind]["event_to_swapped_ms"];
        EXPECT_GE(s["count"].get<int>(), min_count) << kind;
        EXPECT_LE(s["median"].get<double>(), kSlack * load * median_ms) << kind;
        if (p95_ms > 0) {
            EXPECT_LE(s["p95"].get<double>(), kSlack * load * p95_ms) << kind;
        }
        EXPECT_GE(lat[kind]["event_to_shown_ms"]["median"].get<double>(), s["median"].get<double>()) << kind;
    };
    check("point_drag", 100.0, 200.0, 20);
    check("band_slider", 100.0, 0.0, 10);
    check("widget_drag", 250.0, 0.0, 10);
    // The release of each drag (point, widget): its lifts and the full synthesis after the preview.
    check("drag_release", 250.0, 0.0, 2);
    // No frame waits on synthesis: the main thread's own time stays small while dragging.
    for (const char* phase : {"point_drag", "band_slider", "widget_drag"})
        EXPECT_LE(j["frames"][phase]["main_thread_ms"]["p95"].get<double>(), kSlack * load * 8.0) << phase;
    // Only tiles touching the changed windows are rebuilt.
    const auto& tiles = j["tiles"];
    EXPECT_GT(tiles["edits"].get<int>(), 0);
    EXPECT_LE(tiles["rebuilt"].get<int>(), tiles["touching_changed_window"].get<int>());
}

}  // namespace
}  // namespace terrasynth
