// EditSession (issue: one runtime object for the terrain being edited): random scripted sessions
// with exact undo and redo, saving and reopening with the edited-heights sidecar, the height source
// against the session, concurrent tile reads during edits, and bad input.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <set>
#include <thread>
#include <variant>

#include "terrasynth/edit_session.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain.h"
#include "test_support.h"

namespace terrasynth {
namespace {

constexpr int kSize = 192;
constexpr int64_t kOriginX = 1000, kOriginY = -640;

std::string writeProject(const std::string& dir, uint32_t seed = 7, const std::string& constraints = "{}",
                         const std::string& layers = "[]") {
    if (!test::defaultDatabase()) return "";
    Project p;
    p.database = test::defaultDatabasePath();
    p.width = p.height = kSize;
    p.origin_x = kOriginX, p.origin_y = kOriginY;
    p.synthesis.seed = seed;
    p.constraints_json = constraints;
    p.layers_json = layers;
    const std::string path = dir + "/start.tsyn";
    EXPECT_TRUE(saveProject(p, path));
    return path;
}

std::unique_ptr<EditSession> openSession(const std::string& path, std::vector<std::string>* warnings = nullptr,
                                         SynthesisBackend backend = SynthesisBackend::OpenCL) {
    EditSessionOptions options;
    options.synthesizer.backend = backend;
    if (warnings) options.on_warning = [warnings](const std::string& w) { warnings->push_back(w); };
    auto session = EditSession::open(path, options);
    EXPECT_TRUE(session) << session.message();
    return session ? std::move(session.value()) : nullptr;
}

// A random site well inside the extent.
std::pair<double, double> site(std::mt19937& rng, int margin = 24) {
    std::uniform_real_distribution<double> u(margin, kSize - margin);
    return {kOriginX + std::round(u(rng)), kOriginY + std::round(u(rng))};
}

// One random edit of kind `kind` (0..19); returns its name. Edits that the session rightly refuses
// (none are expected here) fail the test.
std::string randomEdit(EditSession& s, std::mt19937& rng, int kind) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const float mean = [&] {
        double sum = 0;
        for (float h : s.heights().heights) sum += h;
        return static_cast<float>(sum / s.heights().heights.size());
    }();
    auto pick = [&](const std::vector<EditId>& ids) { return ids[static_cast<size_t>(unit(rng) * ids.size()) % ids.size()]; };
    auto check = [&](const Result<PixelWindow>& r, const char* name) {
        EXPECT_TRUE(r) << name << ": " << r.message();
        return std::string(name);
    };
    const auto [x, y] = site(rng);
    if (kind == 0 || (kind < 4 && s.pointIds().empty())) {
        PointConstraint p;
        p.x = x, p.y = y, p.height_m = mean + static_cast<float>(600 * (unit(rng) - 0.5));
        p.slope_direction_deg = static_cast<float>(360 * unit(rng)), p.slope_angle_deg = static_cast<float>(10 * unit(rng));
        p.radius_px = static_cast<float>(16 + 30 * unit(rng));
        return check(s.addPoint(p), "addPoint");
    }
    if (kind == 1) return check(s.movePoint(pick(s.pointIds()), x, y), "movePoint");
    if (kind == 2) {
        PointConstraint p = *s.point(pick(s.pointIds()));
        p.height_m += static_cast<float>(200 * (unit(rng) - 0.5));
        p.radius_px = static_cast<float>(16 + 30 * unit(rng));
        return check(s.setPoint(pick(s.pointIds()), p), "setPoint");
    }
    if (kind == 3) return check(s.removePoint(pick(s.pointIds())), "removePoint");
    if (kind == 4 || (kind < 10 && s.curveIds().empty())) {
        CurveConstraint c;
        const auto [x2, y2] = site(rng);
        c.course = {{x, y}, {(x + x2) / 2 + 10, (y + y2) / 2 - 10}, {x2, y2}};
        c.spline = unit(rng) < 0.5;
        CurveWidget a, b;
        a.t = 0.0, a.height_m = mean - 100, a.left_gradient = 0.3f, a.right_gradient = -0.2f;
        b.t = 1.0, b.height_m = mean + 100;
        c.widgets = {a, b};
        return check(s.addCurve(c), "addCurve");
    }
    const EditId curve = kind < 10 ? pick(s.curveIds()) : 0;
    if (kind == 5) return check(s.moveCoursePoint(curve, 1, x, y), "moveCoursePoint");
    if (kind == 6) {
        CurveWidget w;
        w.t = unit(rng), w.height_m = mean + static_cast<float>(300 * (unit(rng) - 0.5)), w.left_reach_px = 20;
        return check(s.addWidget(curve, w), "addWidget");
    }
    if (kind == 7) return check(s.moveWidget(curve, 0, 0.1 * unit(rng)), "moveWidget");
    if (kind == 8) {
        CurveWidget w = s.curve(curve)->widgets.back();
        w.height_m += 150;
        w.right_gradient = -0.5f;
        return check(s.setWidget(curve, static_cast<int>(s.curve(curve)->widgets.size()) - 1, w), "setWidget");
    }
    if (kind == 9) return check(s.removeCurve(curve), "removeCurve");
    const auto [x2, y2] = site(rng);
    if (kind == 10) {
        const auto& names = s.database().type_names;
        return check(s.paintTypes({{x, y}, {x2, y2}}, 10, names[static_cast<size_t>(unit(rng) * names.size()) % names.size()]),
                     "paintTypes");
    }
    if (kind == 11) return check(s.eraseTypes({{x, y}, {x2, y2}}, 8), "eraseTypes");
    if (kind == 12) return check(s.freeze({{x, y}, {x2, y2}}, 6), "freeze");
    if (kind == 13) return check(s.unfreeze({{x, y}}, 20), "unfreeze");
    if (kind == 14 || (kind == 15 && s.pasteIds().empty())) {
        PasteConstraint p;
        const bool exemplar = unit(rng) < 0.5;
        p.exemplar = exemplar ? 1 : -1;
        const double sx = exemplar ? 400 : x, sy = exemplar ? 400 : y;
        p.source = {{sx, sy}, {sx + 20, sy}, {sx + 20, sy + 16}, {sx, sy + 16}};
        p.dx = (x2 - 10) - sx, p.dy = (y2 - 8) - sy;
        p.height_offset_m = static_cast<float>(100 * (unit(rng) - 0.5));
        return check(s.addPaste(p), "addPaste");
    }
    if (kind == 15) return check(s.removePaste(pick(s.pasteIds())), "removePaste");
    if (kind == 16 || (kind < 19 && s.layers().layers.empty())) {
        EditLayer layer;
        PeakParams peak;
        peak.center_x = x - kOriginX, peak.center_y = y - kOriginY, peak.height_m = 300, peak.spread_px = 12;
        layer.tool = peak;
        layer.weights = defaultWeights(layer.tool);
        return check(s.addLayer(layer), "addLayer");
    }
    if (kind == 17) return check(s.setLayerWeights(0, BandWeights{1.0f, static_cast<float>(2 * unit(rng)), 1.0f}), "setLayerWeights");
    if (kind == 18) return check(s.setLayerVisible(0, !s.layers().layers[0].visible), "setLayerVisible");
    return check(s.reseed(static_cast<uint32_t>(1 + unit(rng) * 1000)), "reseed");
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// The long session's edits: every tool the session offers in turn, kinds 0..19 of randomEdit (points,
// curves, type paint, freeze, pastes, a peak layer, band weights, visibility, re-seed) and the layer
// tools and operations 20..31 (ridge, paste from the terrain, flatten, hole fill, noise, replace,
// move, merge, remove, base weights, widget removal, a previewed drag). The working set is bounded as
// a designer's is: beyond 5 points, 3 curves, 3 pastes or 6 layers the edit removes one instead, so
// what grows over thousands of edits is only what the session keeps of its history.
constexpr int kSoakKinds = 32;

std::string soakEdit(EditSession& s, std::mt19937& rng, int step) {
    auto check = [&](const Result<PixelWindow>& r, const char* name) {
        EXPECT_TRUE(r) << "edit " << step << " " << name << ": " << r.message();
        return std::string(name);
    };
    auto last = [](auto ids) { return ids.back(); };
    if (s.pointIds().size() > 5) return check(s.removePoint(last(s.pointIds())), "removePoint (bound)");
    if (s.curveIds().size() > 3) return check(s.removeCurve(last(s.curveIds())), "removeCurve (bound)");
    if (s.pasteIds().size() > 3) return check(s.removePaste(last(s.pasteIds())), "removePaste (bound)");
    const int layers = static_cast<int>(s.layers().layers.size());
    if (layers > 6) return check(s.removeLayer(layers - 1), "removeLayer (bound)");
    const int kind = step % kSoakKinds;
    if (kind < 20) return randomEdit(s, rng, kind);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto local = [&](int margin) {  // extent pixels
        const auto [x, y] = site(rng, margin);
        return std::array<double, 2>{x - kOriginX, y - kOriginY};
    };
    const auto c = local(40);
    auto add = [&](ToolParams tool) {
        const char* type = toolTypeName(tool);
        EditLayer layer;
        layer.name = std::string(type) + " " + std::to_string(step);
        layer.weights = defaultWeights(tool);
        layer.tool = std::move(tool);
        return check(s.addLayer(std::move(layer)), type);
    };
    switch (kind) {
    case 20: {
        RidgeParams ridge;
        ridge.points = {local(30), local(30)};
        ridge.profile_m = {150.0 + 200.0 * unit(rng), 80.0};
        ridge.width_px = 6 + 10 * unit(rng);
        return add(ridge);
    }
    case 21: {
        PasteParams paste;  // a piece of the terrain below, elsewhere
        const auto from = local(40);
        paste.source_x = from[0] - 16, paste.source_y = from[1] - 16;
        paste.dest = Region{RegionShape::Ellipse, c[0] - 16, c[1] - 16, 32, 32};
        paste.vertical_scale = 0.5 + unit(rng);
        return add(paste);
    }
    case 22: {
        PasteParams flatten;  // the editor's flatten tool (editor_ui/src/tools/flatten_tool.cpp)
        flatten.dest = Region{RegionShape::Ellipse, c[0] - 20, c[1] - 20, 40, 40};
        flatten.source_x = flatten.dest.x, flatten.source_y = flatten.dest.y;
        flatten.blend = PasteBlend::Replace;
        flatten.vertical_scale = 0.1;
        flatten.feather_px = 10;
        return add(flatten);
    }
    case 23: {
        HoleFillParams fill;
        fill.hole = Region{RegionShape::Ellipse, c[0] - 12, c[1] - 12, 24, 24};
        fill.patch_px = 16, fill.overlap_px = 4, fill.candidates = 48;
        fill.seed = rng() % 1000;
        fill.choices = {static_cast<int>(rng() % 3)};
        return add(fill);
    }
    case 24: {
        NoiseParams noise;
        noise.fractal.seed = rng() % 1000, noise.fractal.amplitude_m = 40, noise.fractal.wavelength_px = 48;
        noise.fractal.octaves = 4;
        noise.region = Region{RegionShape::Rect, c[0] - 30, c[1] - 30, 60, 60};
        noise.feather_px = 8;
        return add(noise);
    }
    case 25: {
        if (layers == 0) return soakEdit(s, rng, step - 5);  // a peak layer first
        EditLayer changed = s.layers().layers[0];
        if (auto* peak = std::get_if<PeakParams>(&changed.tool)) peak->height_m = 100 + 300 * unit(rng);
        changed.name = "changed at " + std::to_string(step);
        return check(s.replaceLayer(0, changed), "replaceLayer");
    }
    case 26:
        if (layers < 2) return soakEdit(s, rng, step - 6);
        return check(s.moveLayer(layers - 1, 0), "moveLayer");
    case 27:
        if (layers < 2) return soakEdit(s, rng, step - 7);
        return check(s.mergeLayerDown(layers - 1), "mergeLayerDown");
    case 28:
        if (layers == 0) return soakEdit(s, rng, step - 8);
        return check(s.removeLayer(static_cast<int>(rng() % layers)), "removeLayer");
    case 29:
        return check(s.setBaseWeights(BandWeights{1.0f, static_cast<float>(0.5 + unit(rng)), static_cast<float>(0.5 + unit(rng))}),
                     "setBaseWeights");
    case 30: {
        if (s.curveIds().empty()) return randomEdit(s, rng, 4);
        const EditId curve = s.curveIds().front();
        const int widgets = static_cast<int>(s.curve(curve)->widgets.size());
        if (widgets < 3) return randomEdit(s, rng, 6);
        return check(s.removeWidget(curve, widgets / 2), "removeWidget");
    }
    default: {  // a previewed point drag, one undo step, as the editor's point tool makes it
        if (s.pointIds().empty()) return randomEdit(s, rng, 0);
        const EditId id = s.pointIds().front();
        s.beginGesture();
        s.setDragPreviewLevels(1);
        s.deferLifts(true);
        for (int k = 0; k < 4; ++k) {
            const auto [x, y] = site(rng);
            check(s.movePoint(id, x, y), "drag step");
        }
        check(s.liftDeferred(), "liftDeferred");
        s.deferLifts(false);
        s.setDragPreviewLevels(0);
        s.endGesture();
        return "drag";
    }
    }
}

Heightfield extentOf(Terrain& t) {
    auto h = t.heights(t.extent(), 0);
    EXPECT_TRUE(h) << h.message();
    return h ? *h : Heightfield();
}

TEST(EditSession, FortyRandomEditsUndoRedoSaveReopen) {
    const std::string dir = test::scratchDir("session_script");
    const std::string start_path = writeProject(dir);
    ASSERT_FALSE(start_path.empty());
    auto session = openSession(start_path);
    ASSERT_TRUE(session);
    // Opened without a sidecar, the session is exactly what Terrain makes of the project.
    auto fresh = Terrain::open(start_path);
    ASSERT_TRUE(fresh) << fresh.message();
    ASSERT_TRUE(sameBits(session->heights().heights, extentOf(**fresh).heights));

    std::mt19937 rng(20261129);
    std::vector<std::vector<float>> after{session->heights().heights};
    std::vector<std::string> names;
    for (int i = 0; i < 40; ++i) {
        const int kind = i < 20 ? i : static_cast<int>(rng() % 20);
        if (i == 30) {
            // A drag of 8 intermediate positions is one step.
            ASSERT_FALSE(session->pointIds().empty());
            const EditId id = session->pointIds().front();
            session->beginGesture();
            for (int k = 0; k < 8; ++k) ASSERT_TRUE(session->movePoint(id, session->point(id)->x + 2, session->point(id)->y + 1));
            session->endGesture();
            names.push_back("drag");
        } else {
            names.push_back(randomEdit(*session, rng, kind));
        }
        after.push_back(session->heights().heights);
    }
    const uint64_t edits = session->editCount();
    std::printf("undo memory after 40 edits of a %dx%d extent: %.1f bytes per pixel\n", kSize, kSize,
                static_cast<double>(session->undoBytes()) / (kSize * kSize));
    for (int i = 40; i > 0; --i) {
        ASSERT_TRUE(session->canUndo());
        auto undone = session->undo();
        ASSERT_TRUE(undone) << undone.message();
        ASSERT_TRUE(sameBits(session->heights().heights, after[i - 1])) << "undo of edit " << i - 1 << " (" << names[i - 1] << ")";
    }
    EXPECT_FALSE(session->canUndo());
    for (int i = 1; i <= 40; ++i) {
        auto redone = session->redo();
        ASSERT_TRUE(redone) << redone.message();
        ASSERT_TRUE(sameBits(session->heights().heights, after[i])) << "redo of edit " << i - 1 << " (" << names[i - 1] << ")";
    }
    EXPECT_GT(session->editCount(), edits);

    // Saved and reopened, the heights are what the designer saw, through Terrain and a new session.
    const std::string saved = dir + "/edited.tsyn";
    ASSERT_TRUE(session->save(saved));
    EXPECT_FALSE(session->isDirty());
    auto reopened = Terrain::open(saved);
    ASSERT_TRUE(reopened) << reopened.message();
    EXPECT_TRUE(reopened.value()->usesEditedHeights());
    EXPECT_TRUE(reopened.value()->warnings().empty());
    EXPECT_TRUE(sameBits(extentOf(**reopened).heights, after.back()));
    // ... and so is the world around the extent and every coarser level: the same height source.
    const HeightSource source = session->heightSource();
    for (int level = 0; level <= 3; ++level) {
        const PixelWindow around{(kOriginX >> level) - 40, (kOriginY >> level) - 30, (kSize >> level) + 80, 50};
        auto a = source(around, level);
        auto b = reopened.value()->heights(around, level);
        ASSERT_TRUE(a && b);
        EXPECT_TRUE(sameBits(a->heights, b->heights)) << "level " << level;
    }
    auto again = openSession(saved);
    ASSERT_TRUE(again);
    EXPECT_TRUE(sameBits(again->heights().heights, after.back()));
    // The reopened session continues exactly as the first would (same state, same next edit).
    PointConstraint p;
    p.x = kOriginX + 96, p.y = kOriginY + 96, p.height_m = 2500, p.radius_px = 30;
    ASSERT_TRUE(session->addPoint(p));
    ASSERT_TRUE(again->addPoint(p));
    EXPECT_TRUE(sameBits(again->heights().heights, session->heights().heights));

    // Without its sidecar the project is synthesized afresh, with a warning.
    ASSERT_EQ(::unlink((dir + "/edited.heights").c_str()), 0);
    auto lost = Terrain::open(saved);
    ASSERT_TRUE(lost) << lost.message();
    ASSERT_EQ(lost.value()->warnings().size(), 1u);
    EXPECT_NE(lost.value()->warnings()[0].find("edited.heights"), std::string::npos) << lost.value()->warnings()[0];
    Project without = lost.value()->project();
    without.edited_heights.clear();
    auto afresh = Terrain::fromProject(without);
    ASSERT_TRUE(afresh) << afresh.message();
    EXPECT_TRUE(sameBits(extentOf(**lost).heights, extentOf(**afresh).heights));
}

// Resident memory of this process, kB.
size_t residentKb() {
    long pages = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return static_cast<size_t>(resident) * static_cast<size_t>(::sysconf(_SC_PAGESIZE)) / 1024;
}

// Undoes every step the session holds, checking each against the heights recorded after the edits
// (states[i]: after edit i, states[0] before the first), then redoes them all; returns how many
// steps there were.
int undoAllAndRedoAll(EditSession& s, const std::vector<std::vector<float>>& states, size_t first_kept) {
    const size_t last = first_kept + states.size() - 1;  // the newest edit
    int undone = 0;
    while (s.canUndo()) {
        auto r = s.undo();
        EXPECT_TRUE(r) << r.message();
        ++undone;
        const size_t at = last - static_cast<size_t>(undone);
        if (at < first_kept) {
            ADD_FAILURE() << "more undo steps than edits kept";
            return undone;
        }
        if (!sameBits(s.heights().heights, states[at - first_kept])) {
            ADD_FAILURE() << "undo " << undone << " did not give the heights after edit " << at;
            return undone;
        }
    }
    const std::vector<float> oldest = s.heights().heights;
    auto none = s.undo();  // nothing left: no change
    EXPECT_TRUE(none && none->width == 0);
    EXPECT_TRUE(sameBits(s.heights().heights, oldest));
    for (int k = 1; k <= undone; ++k) {
        auto r = s.redo();
        EXPECT_TRUE(r) << r.message();
        const size_t at = last - static_cast<size_t>(undone) + static_cast<size_t>(k);
        if (!sameBits(s.heights().heights, states[at - first_kept])) {
            ADD_FAILURE() << "redo " << k << " did not give the heights after edit " << at;
            return undone;
        }
    }
    EXPECT_FALSE(s.canRedo());
    return undone;
}

// Saved, the heights reopen bit for bit through a new session and through Terrain.
void expectSavedAndReopened(EditSession& s, const std::string& path) {
    ASSERT_TRUE(s.save(path));
    auto again = openSession(path);
    ASSERT_TRUE(again);
    EXPECT_TRUE(sameBits(again->heights().heights, s.heights().heights));
    EXPECT_EQ(again->layers().layers.size(), s.layers().layers.size());
    EXPECT_EQ(again->pointIds().size(), s.pointIds().size());
    auto terrain = Terrain::open(path);
    ASSERT_TRUE(terrain) << terrain.message();
    EXPECT_TRUE(terrain.value()->usesEditedHeights());
    EXPECT_TRUE(sameBits(extentOf(**terrain).heights, s.heights().heights));
}

TEST(EditSession, EveryToolUndoneToTheStartAndRedoneExactly) {
    // Three rounds of every tool (soakEdit), within the longest undo history a session keeps.
    const std::string dir = test::scratchDir("session_every_tool");
    const std::string path = writeProject(dir, 21);
    ASSERT_FALSE(path.empty());
    EditSessionOptions options;
    options.max_undo_steps = 256;
    auto opened = EditSession::open(path, options);
    ASSERT_TRUE(opened) << opened.message();
    EditSession& s = **opened;
    std::mt19937 rng(20261205);
    std::vector<std::vector<float>> states{s.heights().heights};
    std::set<std::string> tools;
    for (int i = 0; i < 3 * kSoakKinds; ++i) {
        tools.insert(soakEdit(s, rng, i));
        states.push_back(s.heights().heights);
        ASSERT_FALSE(HasFailure()) << "edit " << i;
    }
    EXPECT_GE(tools.size(), 30u);
    EXPECT_EQ(undoAllAndRedoAll(s, states, 0), 3 * kSoakKinds);
    expectSavedAndReopened(s, dir + "/edited.tsyn");
}

TEST(EditSession, UndoStopsAtItsByteBudgetWithTheOldestDropped) {
    // EditSessionOptions::max_undo_bytes: a budget of about three point edits' journals keeps the
    // newest steps that fit, exactly undoable, and never holds more (one step alone may exceed it).
    const std::string dir = test::scratchDir("session_undo_budget");
    const std::string path = writeProject(dir, 25);
    ASSERT_FALSE(path.empty());
    EditSessionOptions options;
    auto probe = EditSession::open(path, options);
    ASSERT_TRUE(probe) << probe.message();
    std::mt19937 probe_rng(5);
    randomEdit(**probe, probe_rng, 0);
    const size_t one_step = (*probe)->undoBytes();
    ASSERT_GT(one_step, 0u);
    options.max_undo_bytes = 3 * one_step;
    auto opened = EditSession::open(path, options);
    ASSERT_TRUE(opened) << opened.message();
    EditSession& s = **opened;
    std::mt19937 rng(5);
    std::vector<std::vector<float>> states{s.heights().heights};
    for (int i = 0; i < 12; ++i) {
        randomEdit(s, rng, i % 3);  // add, move and set points
        states.push_back(s.heights().heights);
        EXPECT_LE(s.undoBytes(), options.max_undo_bytes) << "after edit " << i;
    }
    const int kept = undoAllAndRedoAll(s, states, 0);
    std::printf("budget %.1f MB (3 x the first step): %d of 12 steps kept\n", options.max_undo_bytes / 1e6, kept);
    EXPECT_GE(kept, 1);
    EXPECT_LT(kept, 12);
    EXPECT_LE(s.undoBytes(), options.max_undo_bytes);
}

TEST(EditSessionSoak, TwoThousandEditsKeepTheNewestStepsExactlyAndMemoryPlateaus) {
    // A day at the editor: 2,000 edits of every tool with the default undo history
    // (EditSessionOptions::max_undo_steps and max_undo_bytes): undo goes back exactly that many steps, bit for bit,
    // and stops (the oldest were dropped); redo comes back; the memory the history holds and the
    // process's resident memory stop growing once the history is full.
    constexpr int kEdits = 2000;
    const std::string dir = test::scratchDir("session_soak");
    const std::string path = writeProject(dir, 23);
    ASSERT_FALSE(path.empty());
    const EditSessionOptions options;
    const size_t kept = static_cast<size_t>(options.max_undo_steps);
    auto opened = EditSession::open(path, options);
    ASSERT_TRUE(opened) << opened.message();
    EditSession& s = **opened;
    std::mt19937 rng(20261206);
    std::vector<std::vector<float>> states{s.heights().heights};  // the newest kept + 1
    size_t first_state = 0;  // edit index of states[0]
    std::vector<size_t> undo_bytes, resident;  // every 100 edits
    for (int i = 1; i <= kEdits; ++i) {
        soakEdit(s, rng, i - 1);
        ASSERT_FALSE(HasFailure()) << "edit " << i;
        states.push_back(s.heights().heights);
        if (states.size() > kept + 1) states.erase(states.begin()), ++first_state;
        ASSERT_LE(s.undoBytes(), options.max_undo_bytes) << "edit " << i;
        if (i % 100 == 0) {
            undo_bytes.push_back(s.undoBytes());
            resident.push_back(residentKb());
            std::printf("edit %4d: undo history %.1f MB, resident %.1f MB, %zu layers, %zu points\n", i,
                        undo_bytes.back() / 1e6, resident.back() / 1024.0, s.layers().layers.size(), s.pointIds().size());
        }
    }
    EXPECT_EQ(undoAllAndRedoAll(s, states, first_state), options.max_undo_steps);
    expectSavedAndReopened(s, dir + "/edited.tsyn");
    // Plateaus: the second thousand edits hold no more than the first's once the history was full
    // (the same tools in the same cycle, so the same sizes of steps).
    const auto peak = [](const std::vector<size_t>& v, size_t from, size_t to) {
        return *std::max_element(v.begin() + static_cast<long>(from), v.begin() + static_cast<long>(to));
    };
    const size_t full = (kept + 99) / 100;  // samples before the history is full
    EXPECT_LE(peak(undo_bytes, 10, 20), peak(undo_bytes, full, 10) * 5 / 4);
    EXPECT_LE(peak(resident, 10, 20), peak(resident, full, 10) * 11 / 10);
}

TEST(EditSession, ADragWithDeferredLiftsKeepsThemAndLiftsOnceAtTheEnd) {
    // The editor's drags: intermediate moves keep the point's lift (no search), liftDeferred lifts it
    // once, and the site then holds its height as a lifted point does (within 2% of the relief,
    // issue 18); the whole drag, final lift included, is one undo step.
    const std::string dir = test::scratchDir("session_deferred_lifts");
    auto session = openSession(writeProject(dir, 9));
    ASSERT_TRUE(session);
    auto heightAt = [&](const PointConstraint& p) {
        return session->heights().at(static_cast<int>(p.x - kOriginX), static_cast<int>(p.y - kOriginY));
    };
    PointConstraint p;
    p.x = kOriginX + 70.0, p.y = kOriginY + 80.0;
    p.height_m = heightAt(p) + 300.0f;
    p.slope_angle_deg = 0.0f;
    p.radius_px = 40.0f;
    EditId id = 0;
    ASSERT_TRUE(session->addPoint(p, &id));
    const HeightRange relief = heightRange(session->heights());
    const float tolerance = 0.02f * (relief.max - relief.min);
    EXPECT_LT(std::fabs(heightAt(*session->point(id)) - p.height_m), tolerance);
    const std::vector<float> before = session->heights().heights;
    const float lift_before = session->point(id)->lift_m;

    session->beginGesture();
    session->deferLifts(true);
    for (int k = 1; k <= 8; ++k) {
        ASSERT_TRUE(session->movePoint(id, p.x + 4.0 * k, p.y + 3.0 * k));
        EXPECT_EQ(session->point(id)->lift_m, lift_before) << "step " << k << " searched its lift";
    }
    auto lifted = session->liftDeferred();
    ASSERT_TRUE(lifted) << lifted.message();
    EXPECT_GT(lifted->width, 0);
    session->endGesture();
    const PointConstraint& moved = *session->point(id);
    std::printf("site after the drag: %.2f m from its height (relief %.0f m), lift %.1f -> %.1f m\n",
                std::fabs(heightAt(moved) - moved.height_m), relief.max - relief.min, lift_before, moved.lift_m);
    EXPECT_LT(std::fabs(heightAt(moved) - moved.height_m), tolerance);
    // Nothing left deferred: a second call is no edit.
    auto again = session->liftDeferred();
    ASSERT_TRUE(again);
    EXPECT_EQ(again->width, 0);

    ASSERT_TRUE(session->undo());
    EXPECT_EQ(session->heights().heights, before) << "the drag and its final lift were not one undo step";
}

namespace {

// Mean |h - mean of its 3x3| over the pixels within `r` of (cx, cy) (extent pixels): the level-0
// detail the finest correction passes give.
double fineDetail(const Heightfield& h, double cx, double cy, double r) {
    double sum = 0.0;
    int count = 0;
    for (int y = 1; y < h.height - 1; ++y)
        for (int x = 1; x < h.width - 1; ++x) {
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > r * r) continue;
            double mean = 0.0;
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i) mean += h.at(x + i, y + j);
            sum += std::fabs(h.at(x, y) - mean / 9.0);
            ++count;
        }
    return count ? sum / count : 0.0;
}

}  // namespace

TEST(EditSession, APreviewedDragChangesOnlyItsDiscsAndFinishesAsAFullSynthesis) {
    // The editor's drags (--drag-preview-levels 1): every step synthesizes the finest level as a
    // preview (upsampled, not corrected) and changes nothing beyond the discs of the point's old and
    // new site; the gesture's end synthesizes in full, so the site holds its height (2% of the
    // relief, as after any drag) and the finished detail is that of a drag without the preview
    // (level-0 detail within 15%; the preview's own within 50%); the drag stays one undo step.
    const std::string dir = test::scratchDir("session_previewed_drag");
    const std::string path = writeProject(dir, 9);
    auto previewed = openSession(path), full = openSession(path);
    ASSERT_TRUE(previewed && full);
    PointConstraint p;
    p.x = kOriginX + 70.0, p.y = kOriginY + 80.0;
    p.height_m = previewed->heights().at(70, 80) + 300.0f;
    p.slope_angle_deg = 0.0f;
    p.radius_px = 40.0f;
    EditId id = 0, full_id = 0;
    ASSERT_TRUE(previewed->addPoint(p, &id));
    ASSERT_TRUE(full->addPoint(p, &full_id));
    const std::vector<float> before = previewed->heights().heights;
    const HeightRange relief = heightRange(previewed->heights());

    for (EditSession* s : {previewed.get(), full.get()}) {
        s->beginGesture();
        s->setDragPreviewLevels(s == previewed.get() ? 1 : 0);
        s->deferLifts(true);
    }
    double x = p.x, y = p.y;
    for (int k = 1; k <= 8; ++k) {
        const std::vector<float> step_before = previewed->heights().heights;
        const double nx = p.x + 4.0 * k, ny = p.y + 3.0 * k;
        ASSERT_TRUE(previewed->movePoint(id, nx, ny));
        ASSERT_TRUE(full->movePoint(full_id, nx, ny));
        size_t outside_changed = 0, inside = 0, inside_changed = 0;
        for (int py = 0; py < kSize; ++py)
            for (int px = 0; px < kSize; ++px) {
                const double gx = kOriginX + px, gy = kOriginY + py, r2 = p.radius_px * p.radius_px;
                const bool in_disc = (gx - x) * (gx - x) + (gy - y) * (gy - y) <= r2 || (gx - nx) * (gx - nx) + (gy - ny) * (gy - ny) <= r2;
                const size_t i = static_cast<size_t>(py) * kSize + px;
                const bool changed = std::memcmp(&previewed->heights().heights[i], &step_before[i], sizeof(float)) != 0;
                if (in_disc) ++inside, inside_changed += changed;
                else outside_changed += changed;
            }
        EXPECT_EQ(outside_changed, 0u) << "step " << k << " changed pixels beyond the discs";
        EXPECT_GT(inside_changed, inside / 2) << "step " << k;
        x = nx, y = ny;
    }
    const double cx = x - kOriginX, cy = y - kOriginY;
    const double preview_detail = fineDetail(previewed->heights(), cx, cy, p.radius_px);
    for (EditSession* s : {previewed.get(), full.get()}) {
        auto finished = s->liftDeferred();
        ASSERT_TRUE(finished) << finished.message();
        EXPECT_GT(finished->width, 0);
        s->endGesture();
    }
    const PointConstraint& moved = *previewed->point(id);
    const float miss = std::fabs(previewed->heights().at(static_cast<int>(cx), static_cast<int>(cy)) - moved.height_m);
    const double finished_detail = fineDetail(previewed->heights(), cx, cy, p.radius_px);
    const double full_detail = fineDetail(full->heights(), cx, cy, p.radius_px);
    std::printf("site %.2f m from its height (relief %.0f m); level-0 detail: preview %.3f m, finished %.3f m, "
                "drag without preview %.3f m\n",
                miss, relief.max - relief.min, preview_detail, finished_detail, full_detail);
    EXPECT_LT(miss, 0.02f * (relief.max - relief.min));
    EXPECT_NEAR(finished_detail, full_detail, 0.15 * full_detail);
    // The preview shows the exemplars' detail, not upsampling noise (2x2 steps measured 2.5-4x).
    EXPECT_LT(preview_detail, 1.5 * full_detail);
    ASSERT_TRUE(previewed->undo());
    EXPECT_EQ(previewed->heights().heights, before) << "the previewed drag and its finish were not one undo step";
}

// s5.2 through the session: a stroke repainted with another type must change the terrain under it,
// since its pixels now draw from other exemplars (the previous result may not win by coherence).
TEST(EditSession, RepaintingAStrokeWithAnotherTypeChangesIt) {
    const std::string dir = test::scratchDir("session_repaint");
    auto session = openSession(writeProject(dir, 5));
    ASSERT_TRUE(session);
    const std::vector<std::string>& names = session->database().type_names;
    ASSERT_GE(names.size(), 2u);
    const std::vector<std::pair<double, double>> stroke = {{kOriginX + 40.0, kOriginY + 96.0}, {kOriginX + 150.0, kOriginY + 96.0}};
    for (size_t i = 0; i < names.size(); ++i) {
        ASSERT_TRUE(session->paintTypes(stroke, 24, names[i]));
        const std::vector<float> before = session->heights().heights;
        const std::string& next = names[(i + 1) % names.size()];
        auto changed = session->paintTypes(stroke, 24, next);
        ASSERT_TRUE(changed) << changed.message();
        EXPECT_GT(changed->width, 0) << names[i] << " -> " << next << " changed nothing";
        const size_t centre = static_cast<size_t>(96) * kSize + 95;  // on the stroke
        EXPECT_NE(before[centre], session->heights().heights[centre]) << names[i] << " -> " << next;
        ASSERT_TRUE(session->undo());
        ASSERT_TRUE(session->undo());
    }
}

TEST(EditSession, SavedHeightsReopenWithTheMostPassesButNotOnceDrainageIsSwitched) {
    // Breach (the default) and 4 correction passes: the coarsest level's history holds 7 passes
    // (4, 2 more at the coarsest level, the drained state); the sidecar keeps all of them. Its
    // digest holds the drainage: switched off, the project is synthesized afresh.
    const std::string dir = test::scratchDir("session_most_passes");
    Project project;
    project.database = test::defaultDatabasePath();
    project.width = project.height = kSize;
    project.origin_x = kOriginX, project.origin_y = kOriginY;
    project.synthesis.seed = 5;
    project.synthesis.correction_passes = 4;
    ASSERT_EQ(project.synthesis.drainage, Drainage::Breach);
    ASSERT_TRUE(test::defaultDatabase());
    ASSERT_TRUE(saveProject(project, dir + "/start.tsyn"));
    auto session = openSession(dir + "/start.tsyn");
    ASSERT_TRUE(session);
    PointConstraint p;
    p.x = kOriginX + 90, p.y = kOriginY + 80, p.height_m = 2800, p.radius_px = 36;
    ASSERT_TRUE(session->addPoint(p));
    ASSERT_TRUE(session->save(dir + "/edited.tsyn"));
    auto reopened = Terrain::open(dir + "/edited.tsyn");
    ASSERT_TRUE(reopened) << reopened.message();
    for (const std::string& w : reopened.value()->warnings()) ADD_FAILURE() << w;
    EXPECT_TRUE(reopened.value()->usesEditedHeights());
    EXPECT_TRUE(sameBits(extentOf(**reopened).heights, session->heights().heights));
    auto again = openSession(dir + "/edited.tsyn");
    ASSERT_TRUE(again);
    EXPECT_TRUE(sameBits(again->heights().heights, session->heights().heights));
    // Switched to off by hand, the project no longer matches heights synthesized with breach.
    auto edited = loadProject(dir + "/edited.tsyn");
    ASSERT_TRUE(edited) << edited.message();
    edited->synthesis.drainage = Drainage::Off;
    ASSERT_TRUE(saveProject(*edited, dir + "/edited.tsyn"));
    auto switched = Terrain::open(dir + "/edited.tsyn");
    ASSERT_TRUE(switched) << switched.message();
    EXPECT_FALSE(switched.value()->usesEditedHeights());
    ASSERT_EQ(switched.value()->warnings().size(), 1u);
    EXPECT_NE(switched.value()->warnings()[0].find("digest mismatch"), std::string::npos) << switched.value()->warnings()[0];
}

TEST(EditSession, HeightSourceIsTheSessionAndTheWorldAroundIt) {
    const std::string dir = test::scratchDir("session_source");
    auto session = openSession(writeProject(dir, 11));
    ASSERT_TRUE(session);
    PointConstraint p;
    p.x = kOriginX + 60, p.y = kOriginY + 70, p.height_m = 3000, p.radius_px = 40;
    ASSERT_TRUE(session->addPoint(p));
    ASSERT_TRUE(session->paintTypes({{kOriginX + 120.0, kOriginY + 120.0}}, 20, session->database().type_names[0]));
    const HeightSource source = session->heightSource();
    const PixelWindow e = session->extent();
    // Level 0: the session's heights inside; windows overlapping the extent's edge agree bit for bit.
    auto inside = source(e, 0);
    ASSERT_TRUE(inside) << inside.message();
    EXPECT_TRUE(sameBits(inside->heights, session->heights().heights));
    for (int level = 0; level <= 3; ++level) {
        const PixelWindow big{(e.x >> level) - 20, (e.y >> level) - 20, (e.width >> level) + 40, (e.height >> level) + 40};
        const PixelWindow small{big.x + 13, big.y + 7, 37, 29};
        auto a = source(big, level), b = source(small, level);
        ASSERT_TRUE(a && b);
        for (int y = 0; y < small.height; ++y)
            for (int x = 0; x < small.width; ++x)
                ASSERT_EQ(b->at(x, y), a->at(x + 13, y + 7)) << "level " << level << " at " << x << "," << y;
    }
    // heightAt: exact on samples, bilinear between them, also outside the extent.
    const GridFrame f = session->frame();
    auto at = session->heightAt(f.worldX(static_cast<double>(e.x + 5)), f.worldY(static_cast<double>(e.y + 9)));
    ASSERT_TRUE(at);
    EXPECT_EQ(static_cast<float>(*at), session->heights().at(5, 9));
    auto mid = session->heightAt(f.worldX(e.x + 5.5), f.worldY(e.y + 9.0));
    ASSERT_TRUE(mid);
    EXPECT_NEAR(*mid, 0.5 * (session->heights().at(5, 9) + session->heights().at(6, 9)), 1e-3);
    auto outside = session->heightAt(f.worldX(e.x - 500.0), f.worldY(e.y - 300.0));
    ASSERT_TRUE(outside) << outside.message();
    auto world = source({e.x - 500, e.y - 300, 1, 1}, 0);
    ASSERT_TRUE(world);
    EXPECT_EQ(static_cast<float>(*outside), world->at(0, 0));
}

TEST(EditSession, TilesReadOnTwoThreadsWhileEditsRun) {
    // The C++ backend, so a ThreadSanitizer build (-DTERRASYNTH_SANITIZE=thread) sees every access.
    const std::string dir = test::scratchDir("session_threads");
    auto session = openSession(writeProject(dir, 5), nullptr, SynthesisBackend::Reference);
    ASSERT_TRUE(session);
    std::atomic<bool> stop{false};
    std::atomic<int> reads{0}, failures{0};
    auto reader = [&](int seed) {
        std::mt19937 rng(seed);
        while (!stop) {
            const int level = static_cast<int>(rng() % 3);
            const PixelWindow w{(kOriginX >> level) + static_cast<int>(rng() % 100) - 30,
                                (kOriginY >> level) + static_cast<int>(rng() % 100) - 30, 48, 48};
            auto h = session->heightSource()(w, level);
            auto at = session->heightAt(session->frame().worldX(kOriginX + 50.5), session->frame().worldY(kOriginY + 60.5));
            if (!h || !at || !std::isfinite(*at)) ++failures;
            ++reads;
        }
    };
    std::thread a(reader, 1), b(reader, 2);
    std::mt19937 rng(9);
    for (int i = 0; i < 12; ++i) randomEdit(*session, rng, i % 2 == 0 ? 0 : (i % 4 == 1 ? 1 : 10));
    ASSERT_TRUE(session->undo());
    ASSERT_TRUE(session->redo());
    stop = true;
    a.join();
    b.join();
    EXPECT_EQ(failures.load(), 0);
    EXPECT_GT(reads.load(), 10);
}

TEST(EditSession, BadInputIsRefusedAndChangesNothing) {
    const std::string dir = test::scratchDir("session_bad");
    auto session = openSession(writeProject(dir, 3));
    ASSERT_TRUE(session);
    PointConstraint ok;
    ok.x = kOriginX + 50, ok.y = kOriginY + 50, ok.height_m = 2000;
    EditId point = 0, curve = 0;
    ASSERT_TRUE(session->addPoint(ok, &point));
    CurveConstraint c;
    c.course = {{kOriginX + 20.0, kOriginY + 30.0}, {kOriginX + 150.0, kOriginY + 40.0}};
    c.widgets = {CurveWidget{}};
    c.widgets[0].height_m = 1500;
    ASSERT_TRUE(session->addCurve(c, &curve));
    const std::vector<float> heights = session->heights().heights;
    const uint64_t count = session->editCount();
    const std::string project_json = session->project().constraints_json;

    auto refused = [&](const Result<PixelWindow>& r, const char* fragment) {
        ASSERT_FALSE(r) << fragment;
        EXPECT_NE(r.message().find(fragment), std::string::npos) << r.message();
        EXPECT_TRUE(sameBits(session->heights().heights, heights)) << fragment;
        EXPECT_EQ(session->editCount(), count) << fragment;
        EXPECT_EQ(session->project().constraints_json, project_json) << fragment;
    };
    PointConstraint bad = ok;
    bad.height_m = 50000;
    refused(session->addPoint(bad), "point.height_m");
    bad = ok, bad.slope_angle_deg = 85;
    refused(session->setPoint(point, bad), "point.slope_angle_deg");
    bad = ok, bad.radius_px = 0;
    refused(session->addPoint(bad), "point.radius_px");
    bad = ok, bad.x = std::nan("");
    refused(session->addPoint(bad), "point.x");
    refused(session->movePoint(point, 1e12, 0), "point.x");
    refused(session->movePoint(point + 1000, 10, 10), "no such point");
    refused(session->removePoint(999), "no such point");
    refused(session->removeCurve(998), "no such curve");
    refused(session->moveCoursePoint(curve, 7, 0, 0), "course point 7");
    refused(session->moveWidget(curve, 3, 0.5), "widget 3");
    refused(session->removeWidget(curve, 0), "at least one widget");
    CurveWidget w;
    w.left_gradient = 50;
    refused(session->addWidget(curve, w), "left_gradient");
    CurveConstraint one_point = c;
    one_point.course.resize(1);
    refused(session->setCurve(curve, one_point), "curve.course");
    refused(session->paintTypes({{kOriginX + 10.0, kOriginY + 10.0}}, 5, "lava"), "type \"lava\"");
    refused(session->paintTypes({}, 5, session->database().type_names[0]), "stroke");
    refused(session->freeze({{kOriginX + 10.0, kOriginY + 10.0}}, -3), "stroke.radius_px");
    PasteConstraint paste;
    paste.exemplar = 0;
    paste.source = {{0, 0}, {900, 0}, {900, 900}, {0, 900}};  // far beyond the exemplar
    paste.dx = kOriginX, paste.dy = kOriginY;
    refused(session->addPaste(paste), "leaves exemplar");
    paste.exemplar = 40;
    refused(session->addPaste(paste), "paste.exemplar");
    refused(session->removePaste(5), "no such paste");
    refused(session->setLayerWeights(3, BandWeights{}), "layer index 3");
    refused(session->removeLayer(0), "layer index 0");
    // Saving where a file stands in for the folder: an error naming it, nothing written (not even
    // the folders below it), still dirty.
    EXPECT_TRUE(session->isDirty());
    ASSERT_TRUE(writeFileAtomically(dir + "/blocker", "a file"));
    Status unwritable = session->save(dir + "/blocker/missing/edited.tsyn");
    ASSERT_FALSE(unwritable);
    EXPECT_NE(unwritable.message().find(dir + "/blocker is a file, not a folder"), std::string::npos) << unwritable.message();
    EXPECT_TRUE(session->isDirty());
    EXPECT_EQ(*readFileBytes(dir + "/blocker"), "a file");
    EXPECT_FALSE(session->save(dir + "/edited.txt"));
    // A good save still works after all that, and a second one is skipped when nothing changed.
    ASSERT_TRUE(session->save(dir + "/edited.tsyn"));
    bool wrote = true;
    ASSERT_TRUE(session->saveIfDirty(dir + "/edited.tsyn", &wrote));
    EXPECT_FALSE(wrote);
    // Into folders that do not exist yet: they are made, and the project reopens with its heights.
    ASSERT_TRUE(session->save(dir + "/new/deeper/edited.tsyn"));
    auto reopened = openSession(dir + "/new/deeper/edited.tsyn");
    ASSERT_TRUE(reopened);
    EXPECT_TRUE(sameBits(reopened->heights().heights, session->heights().heights));
}

TEST(EditSession, AFullDiskOrReadOnlyFolderFailsTheSaveNamingTheFileAndKeepsTheOldOnes) {
    // The editor's save and autosave (save, saveIfDirty) on a small filesystem of our own: a tmpfs
    // mounted in a private user and mount namespace, where this test runs itself again.
    TERRASYNTH_ON_A_PRIVATE_TMPFS(small, "EditSession.AFullDiskOrReadOnlyFolderFailsTheSaveNamingTheFileAndKeepsTheOldOnes",
                                  "session_disk_faults", "48m");
    auto session = openSession(writeProject(test::scratchDir("session_disk_faults_project"), 27));
    ASSERT_TRUE(session);
    std::mt19937 rng(27);
    randomEdit(*session, rng, 0);
    const std::string saved = small + "/edited.tsyn", autosave = small + "/edited.autosave.tsyn";
    ASSERT_TRUE(session->save(saved));
    randomEdit(*session, rng, 16);
    bool wrote = false;
    ASSERT_TRUE(session->saveIfDirty(autosave, &wrote));
    ASSERT_TRUE(wrote);
    const std::vector<std::string> files = test::filesUnder(small);
    std::vector<std::string> bytes;
    for (const std::string& f : files) bytes.push_back(test::readFile(small + "/" + f));
    auto intact = [&](const char* when) {
        EXPECT_EQ(test::filesUnder(small).size(), files.size() + (std::string(when) == "full" ? 1 : 0)) << when << ": temporaries left";
        for (size_t i = 0; i < files.size(); ++i) EXPECT_EQ(test::readFile(small + "/" + files[i]), bytes[i]) << when << ": " << files[i];
    };
    const std::vector<float> edited_heights = (randomEdit(*session, rng, 1), session->heights().heights);

    // Full: both saves fail naming a file of theirs, the old files are as they were, the session
    // stays dirty and edits on; with room again the same save works.
    ASSERT_NE(std::system(("dd if=/dev/zero of='" + small + "/filler' bs=64k 2>/dev/null").c_str()), -1);
    for (const std::string& path : {saved, autosave}) {
        const Status full = session->save(path);
        ASSERT_FALSE(full) << path;
        EXPECT_NE(full.message().find(small + "/edited"), std::string::npos) << full.message();
        EXPECT_NE(full.message().find("disk full"), std::string::npos) << full.message();
        std::printf("full disk: %s\n", full.message().c_str());
    }
    EXPECT_FALSE(session->saveIfDirty(autosave));
    EXPECT_TRUE(session->isDirty());
    intact("full");
    ASSERT_TRUE(session->undo());
    ASSERT_TRUE(session->redo());
    EXPECT_TRUE(sameBits(session->heights().heights, edited_heights));
    ASSERT_EQ(::unlink((small + "/filler").c_str()), 0);
    ASSERT_TRUE(session->save(saved));
    auto reopened = openSession(saved);
    ASSERT_TRUE(reopened);
    EXPECT_TRUE(sameBits(reopened->heights().heights, edited_heights));

    // Read-only: the same.
    randomEdit(*session, rng, 10);
    for (size_t i = 0; i < files.size(); ++i) bytes[i] = test::readFile(small + "/" + files[i]);
    ASSERT_EQ(std::system(("mount -o remount,ro '" + small + "'").c_str()), 0);
    const Status readonly = session->saveIfDirty(autosave);
    ASSERT_FALSE(readonly);
    EXPECT_NE(readonly.message().find(small + "/edited.autosave."), std::string::npos) << readonly.message();
    EXPECT_NE(readonly.message().find("Read-only file system"), std::string::npos) << readonly.message();
    std::printf("read-only folder: %s\n", readonly.message().c_str());
    intact("read-only");
    EXPECT_TRUE(session->isDirty());
    const std::string elsewhere = test::scratchDir("session_disk_faults_elsewhere") + "/edited.tsyn";
    ASSERT_TRUE(session->save(elsewhere));  // still usable: saved where there is room
    EXPECT_FALSE(session->isDirty());
}

TEST(EditSession, ConstraintsFromAProjectRoundTripThroughTheSession) {
    const std::string dir = test::scratchDir("session_project");
    const std::string constraints = R"({"points": [{"x": 40, "y": 50, "height_m": 2600, "radius_px": 30}],
        "types": {"strokes": [{"type": "alpine ranges", "radius_px": 12, "points": [[100, 100], [150, 120]]}]},
        "freeze": {"strokes": [{"radius_px": 6, "points": [[20, 150], [60, 160]]}]},
        "pastes": [{"exemplar": "orom_rockies", "source": [[400, 400], [430, 400], [430, 420], [400, 420]], "target": [110, 20]}]})";
    const std::string layers = R"([{"type": "peak", "center": [90, 90], "height_m": 200, "spread_px": 10}])";
    const std::string path = writeProject(dir, 13, constraints, layers);
    auto session = openSession(path);
    ASSERT_TRUE(session);
    // The session starts from exactly what Terrain makes of the project (freeze, paste, layers).
    auto terrain = Terrain::open(path);
    ASSERT_TRUE(terrain) << terrain.message();
    EXPECT_TRUE(sameBits(session->heights().heights, extentOf(**terrain).heights));
    EXPECT_EQ(session->pointIds().size(), 1u);
    EXPECT_EQ(session->pasteIds().size(), 1u);
    EXPECT_EQ(session->layers().layers.size(), 1u);
    // Saved without edits: the written project parses to the same constraints (painting as masks).
    ASSERT_TRUE(session->save(dir + "/copy.tsyn"));
    auto copy = Terrain::open(dir + "/copy.tsyn");
    ASSERT_TRUE(copy) << copy.message();
    const auto& a = *session->project().synthesis.constraints;
    const auto& b = *copy.value()->project().synthesis.constraints;
    EXPECT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(a.types.types, b.types.types);
    EXPECT_TRUE(sameBits(extentOf(**copy).heights, session->heights().heights));
}

}  // namespace
}  // namespace terrasynth
