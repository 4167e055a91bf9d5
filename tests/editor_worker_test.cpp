// The editor's edit thread (terrasynth_editor/edit_worker.h) on a real session and a real terrain
// node driven headlessly: latest-wins coalescing of drags, gestures as one undo step, failed edits
// that change nothing, the terrain told exactly what changed (only tiles touching it rebuilt), the
// overlay masks, and the latency bookkeeping on top.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "terrasynth/edit_session.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth_editor/edit_worker.h"
#include "terrasynth_editor/latency.h"
#include "headless_view.h"
#include "test_support.h"
#include "wait_until.h"

namespace terrasynth::editor {
namespace {

constexpr int kSize = 256;

std::string writeProject(const std::string& dir) {
    if (!test::defaultDatabase()) return "";
    Project p;
    p.database = test::defaultDatabasePath();
    p.width = p.height = kSize;
    p.synthesis.seed = 3;
    const std::string path = dir + "/worker.tsyn";
    EXPECT_TRUE(saveProject(p, path));
    return path;
}

std::unique_ptr<EditWorker> openWorker(const std::string& path) {
    auto worker = std::make_unique<EditWorker>([path](const auto&) { return EditSession::open(path); });
    EXPECT_TRUE(worker->waitIdle(300.0));
    EXPECT_EQ(worker->state(), EditWorker::State::Ready) << worker->openError();
    return worker;
}

// A request that copies the session's heights (what the edit thread sees).
Heightfield heightsOf(EditWorker& worker) {
    auto out = std::make_shared<Heightfield>();
    EditRequest r;
    r.label = "read heights";
    r.run = [out](EditSession& s) -> Result<PixelWindow> {
        *out = s.heights();
        return PixelWindow{};
    };
    worker.submit(std::move(r));
    EXPECT_TRUE(worker.waitIdle(120.0));
    worker.takeResults();
    return *out;
}

EditRequest request(const std::string& label, std::function<Result<PixelWindow>(EditSession&)> run,
                    const std::string& key = "") {
    EditRequest r;
    r.label = label;
    r.coalesce_key = key;
    r.run = std::move(run);
    return r;
}

TEST(EditorWorker, DragsCoalesceLatestWinsAndAGestureIsOneUndoStep) {
    const std::string path = writeProject(test::scratchDir("editor_worker_drag"));
    ASSERT_FALSE(path.empty());
    auto worker = openWorker(path);
    const Heightfield start = heightsOf(*worker);

    auto id = std::make_shared<EditId>(0);
    PointConstraint p;
    p.x = 128, p.y = 128, p.height_m = start.at(128, 128) + 400.0f, p.radius_px = 24;
    worker->submit(request("add point", [p, id](EditSession& s) { return s.addPoint(p, id.get()); }));
    ASSERT_TRUE(worker->waitIdle(120.0));
    ASSERT_TRUE(worker->takeResults().front().status);
    const Heightfield added = heightsOf(*worker);

    // Hold the edit thread, then queue a drag of 30 moves: only the newest waits at the tail. The
    // thread is held until all 30 are queued (a latch, not a sleep: on a loaded machine the queueing
    // may take longer than any pause).
    auto held = std::make_shared<std::atomic<bool>>(false), released = std::make_shared<std::atomic<bool>>(false);
    worker->submit(request("gesture", [held, released](EditSession& s) -> Result<PixelWindow> {
        s.beginGesture();
        *held = true;
        EXPECT_TRUE(test::waitUntil([&] { return released->load(); }));
        return PixelWindow{};
    }));
    ASSERT_TRUE(test::waitUntil([&] { return held->load(); }));
    for (int i = 1; i <= 30; ++i) {
        const double x = 128 + i, y = 128 + i / 2;
        worker->submit(request("move point", [id, x, y](EditSession& s) { return s.movePoint(*id, x, y); }, "drag"));
    }
    *released = true;
    worker->submit(request("gesture", [](EditSession& s) -> Result<PixelWindow> {
        s.endGesture();
        return PixelWindow{};
    }));
    ASSERT_TRUE(worker->waitIdle(120.0));
    const std::vector<EditResult> results = worker->takeResults();
    int moves = 0, superseded = 0;
    for (const EditResult& r : results) {
        EXPECT_TRUE(r.status) << r.label << ": " << r.status.message();
        if (r.label != "move point") continue;
        ++moves;
        superseded += r.superseded;
        EXPECT_FALSE(r.changed.empty());
    }
    EXPECT_EQ(moves, 1) << "the 30 queued moves should have collapsed into the newest";
    EXPECT_EQ(superseded, 29);
    const auto view = worker->view();
    ASSERT_EQ(view->points.size(), 1u);
    EXPECT_EQ(view->points[0].point.x, 158.0);
    EXPECT_EQ(view->points[0].point.y, 143.0);

    // The whole drag is one undo step: undo puts the point back, bit for bit.
    worker->submit(request("undo", [](EditSession& s) { return s.undo(); }));
    ASSERT_TRUE(worker->waitIdle(120.0));
    worker->takeResults();
    EXPECT_EQ(heightsOf(*worker).heights, added.heights);
    EXPECT_EQ(worker->view()->points[0].point.x, 128.0);
}

TEST(EditorWorker, FailedEditsChangeNothingAndReportTheirStatus) {
    const std::string path = writeProject(test::scratchDir("editor_worker_fail"));
    ASSERT_FALSE(path.empty());
    auto worker = openWorker(path);
    const Heightfield start = heightsOf(*worker);
    const uint64_t count = worker->view()->edit_count;
    bool done_called = false;
    EditRequest r = request("move point", [](EditSession& s) { return s.movePoint(12345, 10, 10); });
    r.done = [&](const EditResult& res) { done_called = !res.status; };
    worker->submit(std::move(r));
    PointConstraint bad;
    bad.x = 100, bad.y = 100, bad.radius_px = 0.0f;  // radius must be > 0
    worker->submit(request("add point", [bad](EditSession& s) { return s.addPoint(bad); }));
    // An exception in a request is a failed request, not a dead edit thread.
    worker->submit(request("throw", [](EditSession&) -> Result<PixelWindow> { throw std::runtime_error("boom"); }));
    ASSERT_TRUE(worker->waitIdle(120.0));
    const auto results = worker->takeResults();
    ASSERT_EQ(results.size(), 3u);
    EXPECT_TRUE(done_called);
    for (const EditResult& res : results) {
        EXPECT_FALSE(res.status) << res.label;
        EXPECT_EQ(res.generation, 0u);
    }
    EXPECT_NE(results[1].status.message().find("radius"), std::string::npos) << results[1].status.message();
    EXPECT_NE(results[2].status.message().find("boom"), std::string::npos);
    EXPECT_EQ(worker->view()->edit_count, count);
    EXPECT_EQ(heightsOf(*worker).heights, start.heights);

    // A failed save says why and leaves the session dirty.
    PointConstraint good;
    good.x = 100, good.y = 100, good.height_m = start.at(100, 100) + 50.0f, good.radius_px = 10;
    worker->submit(request("add point", [good](EditSession& s) { return s.addPoint(good); }));
    // A file where the save's folder should be (a missing folder would be made).
    const std::string blocker = test::scratchDir("editor_worker_fail") + "/blocker";
    ASSERT_TRUE(writeFileAtomically(blocker, "a file"));
    const std::string bad_path = blocker + "/folder/w.tsyn";
    worker->submit(request("save", [bad_path](EditSession& s) -> Result<PixelWindow> {
        if (Status st = s.save(bad_path); !st) return st;
        return PixelWindow{};
    }));
    ASSERT_TRUE(worker->waitIdle(120.0));
    const auto saved = worker->takeResults();
    ASSERT_EQ(saved.size(), 2u);
    EXPECT_TRUE(saved[0].status) << saved[0].status.message();
    EXPECT_FALSE(saved[1].status);
    EXPECT_NE(saved[1].status.message().find("blocker is a file"), std::string::npos) << saved[1].status.message();
    EXPECT_TRUE(worker->view()->dirty);
}

TEST(EditorWorker, TheTerrainRebuildsOnlyTilesTouchingTheChangedWindow) {
    const std::string path = writeProject(test::scratchDir("editor_worker_tiles"));
    ASSERT_FALSE(path.empty());
    auto worker = openWorker(path);
    const auto view = worker->view();
    plugin::TerrainNodeOptions o;
    o.tile_size = 32;
    o.max_level = 3;
    o.threads = 2;
    o.view_radius_m = 2.0 * kSize * view->frame.meters_per_pixel;
    osg::ref_ptr<plugin::TerrainNode> node = new plugin::TerrainNode(worker->heightSource(), view->frame.meters_per_pixel, o);
    worker->attachTerrain(node);
    test::HeadlessView headless(node.get(), 640, 360, 40.0);
    const GridFrame f = view->frame;
    const osg::Vec3d centre(f.worldX(kSize / 2), f.worldY(kSize / 2), 0.5 * (view->min_height_m + view->max_height_m));
    const osg::Vec3d eye = centre + osg::Vec3d(0.0, -12000.0, 25000.0);
    // Until the view has converged (tiles of 32 samples cost their margins' work many times over,
    // the breach's, the default, above all); waitUntil's deadline only stops a hung run.
    auto settle = [&] {
        int frames = 0;
        return test::waitUntil([&] {
            headless.frame(eye, centre);
            return ++frames > 4 && node->settled();
        });
    };
    ASSERT_TRUE(settle());
    const plugin::TerrainStats before = node->stats();
    ASSERT_GT(before.drawn_tiles, 8u);

    // The session's level-0 height at a pixel, read on the edit thread.
    auto at = [&](double px, double py) -> double {
        auto out = std::make_shared<double>(0.0);
        worker->submit(request("height", [out, f, px, py](EditSession& s) -> Result<PixelWindow> {
            auto h = s.heightAt(f.worldX(px), f.worldY(py));
            if (!h) return h.status();
            *out = *h;
            return PixelWindow{};
        }));
        worker->waitIdle(60.0);
        worker->takeResults();
        return *out;
    };
    PointConstraint p;
    p.x = 60, p.y = 70, p.height_m = view->max_height_m + 200.0f, p.radius_px = 12;
    const double session_before = at(p.x, p.y);
    const auto drawn_before = node->heightAt(f.worldX(p.x), f.worldY(p.y));
    ASSERT_TRUE(drawn_before.has_value());
    worker->submit(request("add point", [p](EditSession& s) { return s.addPoint(p); }));
    ASSERT_TRUE(worker->waitIdle(120.0));
    const EditResult r = worker->takeResults().front();
    ASSERT_TRUE(r.status) << r.status.message();
    ASSERT_GT(r.generation, 0u);
    EXPECT_EQ(r.invalidated, r.changed);
    EXPECT_GT(r.tiles_marked, 0u);
    EXPECT_LT(r.tiles_marked, r.tiles_drawn) << "a local edit must not mark every tile in view";
    ASSERT_TRUE(settle());
    EXPECT_EQ(node->tilesAwaitingRebuild(r.generation), 0u);
    const plugin::TerrainStats after = node->stats();
    EXPECT_LE(after.tiles_built - before.tiles_built, r.tiles_marked);
    EXPECT_GT(after.tiles_swapped, before.tiles_swapped);
    // The drawn surface rose with the session's heights at the site (as far as the level drawn
    // there resolves a peak of this radius).
    const double session_rise = at(p.x, p.y) - session_before;
    const auto drawn_after = node->heightAt(f.worldX(p.x), f.worldY(p.y));
    ASSERT_TRUE(drawn_after.has_value());
    ASSERT_GT(session_rise, 100.0);
    EXPECT_GT(*drawn_after - *drawn_before, 0.5 * session_rise) << "the swapped tiles must show the edit";
}

TEST(EditorWorker, OverlayMasksFollowFreezingPaintingAndUndo) {
    const std::string path = writeProject(test::scratchDir("editor_worker_masks"));
    ASSERT_FALSE(path.empty());
    auto worker = openWorker(path);
    const auto view = worker->view();
    EditRequest freeze = request("freeze", [](EditSession& s) { return s.freeze({{40, 40}, {80, 40}}, 6); });
    freeze.refresh_masks = true;
    worker->submit(std::move(freeze));
    const std::string type = view->database->type_names.back();
    EditRequest paint = request("paint", [type](EditSession& s) { return s.paintTypes({{150, 150}, {150, 190}}, 5, type); });
    paint.refresh_masks = true;
    worker->submit(std::move(paint));
    ASSERT_TRUE(worker->waitIdle(300.0));
    const auto results = worker->takeResults();
    ASSERT_EQ(results.size(), 2u);
    for (const EditResult& r : results) ASSERT_TRUE(r.status) << r.status.message();
    // A freeze changes no height, but the overlay changed: the terrain is told to rebuild there.
    EXPECT_TRUE(results[0].changed.empty());
    EXPECT_TRUE(results[0].invalidated.contains(60, 40));
    auto masks = worker->masks();
    ASSERT_TRUE(masks);
    const auto at = [&](const std::vector<uint8_t>& plane, int x, int y) { return plane[static_cast<size_t>(y) * kSize + x]; };
    EXPECT_EQ(at(masks->frozen, 60, 40), 1);
    EXPECT_EQ(at(masks->frozen, 60, 60), 0);
    EXPECT_EQ(at(masks->painted, 150, 170), static_cast<uint8_t>(view->database->type_names.size() - 1));
    EXPECT_EQ(at(masks->painted, 100, 100), TypePaint::kUnpainted);

    EditRequest undo = request("undo", [](EditSession& s) { return s.undo(); });
    undo.refresh_masks = true;
    worker->submit(std::move(undo));
    ASSERT_TRUE(worker->waitIdle(300.0));
    worker->takeResults();
    masks = worker->masks();
    EXPECT_EQ(at(masks->painted, 150, 170), TypePaint::kUnpainted);
    EXPECT_EQ(at(masks->frozen, 60, 40), 1);
}

TEST(EditorLatency, InputsResolveWhenTheirEditsTilesAreSwappedThenShown) {
    LatencyTracker t;
    const uint64_t a = t.noteInput(InputKind::PointDrag, 10.0);
    const uint64_t b = t.noteInput(InputKind::PointDrag, 10.02);
    const uint64_t c = t.noteInput(InputKind::BandSlider, 10.03);
    EXPECT_EQ(a, 1u);
    EXPECT_EQ(b, 2u);
    EXPECT_EQ(c, 1u);
    // One request answered both drag inputs (latest wins); its tiles need two UPDATEs.
    EditResult r;
    r.input_seq = b;
    r.input_kind = static_cast<int>(InputKind::PointDrag);
    r.generation = 7;
    r.finished_at_s = 10.05;
    r.run_ms = 25.0;
    t.noteResult(r);
    EditResult failed;
    failed.input_seq = c;
    failed.input_kind = static_cast<int>(InputKind::BandSlider);
    failed.status = Status::error("no");
    t.noteResult(failed);
    size_t awaiting = 3;
    t.afterUpdate([&](uint64_t g) { return g == 7 ? awaiting : 0; }, 10.08);
    t.afterFrame(10.09);
    EXPECT_TRUE(t.samples(InputKind::PointDrag).empty());
    awaiting = 0;
    t.afterUpdate([&](uint64_t g) { return g == 7 ? awaiting : 0; }, 10.10);
    EXPECT_TRUE(t.pending());
    t.afterFrame(10.15);
    EXPECT_FALSE(t.pending());
    const auto& s = t.samples(InputKind::PointDrag);
    ASSERT_EQ(s.size(), 2u);
    EXPECT_NEAR(s[0].applied_ms, 50.0, 1e-6);
    EXPECT_NEAR(s[0].swapped_ms, 100.0, 1e-6);
    EXPECT_NEAR(s[0].shown_ms, 150.0, 1e-6);
    EXPECT_NEAR(s[1].swapped_ms, 80.0, 1e-6);
    EXPECT_EQ(s[1].edit_ms, 25.0);
    EXPECT_TRUE(t.samples(InputKind::BandSlider).empty()) << "a failed edit shows nothing";
}

}  // namespace
}  // namespace terrasynth::editor
