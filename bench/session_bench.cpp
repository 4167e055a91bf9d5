// The edit session on the default 1024^2 project: a point drag step, its undo, heightAt, and the
// memory 100 undo steps hold. Targets (issue): drag step <= 40 ms median, undo <= 10 ms,
// heightAt <= 1 us where the pixel is resident.
// Run: build/bin/session_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>

#include "terrasynth/edit_session.h"

using namespace terrasynth;

namespace {

// One session shared by the benchmarks (opening synthesizes the 1024^2 extent once).
EditSession* session(benchmark::State& state) {
    static std::unique_ptr<EditSession> shared = [] {
        ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
        auto project = loadProject(std::string(TERRASYNTH_BENCH_DATA_DIR) + "/default.tsyn");
        if (!project) return std::unique_ptr<EditSession>();
        project->database = std::string(TERRASYNTH_BENCH_POCL_CACHE) + "/../bench_default.tsdb";
        auto s = EditSession::fromProject(std::move(project.value()));
        return s ? std::move(s.value()) : std::unique_ptr<EditSession>();
    }();
    if (!shared) state.SkipWithError("cannot open data/default.tsyn");
    return shared.get();
}

EditId dragged(EditSession& s) {
    static EditId id = 0;
    if (id) return id;
    PointConstraint p;
    p.x = 512, p.y = 512, p.height_m = s.heights().at(512, 512) + 300.0f, p.radius_px = 64;
    if (s.addPoint(p, &id)) return id;
    return 0;
}

// Drag step `step` of a gesture: the point moves a few pixels (what one mouse event between frames
// does), cycling over a small pattern around the extent's centre.
void dragStep(benchmark::State& state, EditSession& s, EditId id, int step) {
    auto r = s.movePoint(id, 512 + 3.0 * (step % 8), 512 + 2.0 * ((step / 8) % 4));
    if (!r) state.SkipWithError(r.message().c_str());
}

// A gesture as the editor starts a drag: with `defer` the steps keep their lifts, with
// `preview_levels` they preview that many finest levels (EditSession::setDragPreviewLevels).
void beginDrag(EditSession& s, bool defer, int preview_levels) {
    s.beginGesture();
    s.setDragPreviewLevels(preview_levels);
    s.deferLifts(defer);
}

}  // namespace

// Drag steps of one gesture; with `defer` as the editor drags (EditSession::deferLifts): a step
// keeps the point's lift instead of searching it, and the final lift is one edit when the drag ends
// (not timed).
static void dragGesture(benchmark::State& state, bool defer, int preview_levels = 0) {
    EditSession* s = session(state);
    if (!s) return;
    const EditId id = dragged(*s);
    int step = 0;
    beginDrag(*s, defer, preview_levels);
    for (auto _ : state) dragStep(state, *s, id, step++);
    if (auto lifted = s->liftDeferred(); !lifted) state.SkipWithError(lifted.message().c_str());
    s->endGesture();
}

static void BM_PointDragStep(benchmark::State& state) { dragGesture(state, false); }
BENCHMARK(BM_PointDragStep)->Unit(benchmark::kMillisecond)->UseRealTime();
static void BM_PointDragStepDeferredLifts(benchmark::State& state) { dragGesture(state, true); }
BENCHMARK(BM_PointDragStepDeferredLifts)->Unit(benchmark::kMillisecond)->UseRealTime();
// ... and with the editor's preview: the finest level upsampled, not corrected, until the drag ends.
static void BM_PointDragStepPreview(benchmark::State& state) { dragGesture(state, true, 1); }
BENCHMARK(BM_PointDragStepPreview)->Unit(benchmark::kMillisecond)->UseRealTime();

// The end of a previewed drag: the lift and full re-synthesis of what its steps changed (the editor's
// gesture end; the drag is 8 steps, not timed).
static void BM_PreviewedDragFinish(benchmark::State& state) {
    EditSession* s = session(state);
    if (!s) return;
    const EditId id = dragged(*s);
    int step = 0;
    for (auto _ : state) {
        state.PauseTiming();
        beginDrag(*s, true, 1);
        for (int i = 0; i < 8; ++i) dragStep(state, *s, id, step++);
        state.ResumeTiming();
        if (auto lifted = s->liftDeferred(); !lifted) state.SkipWithError(lifted.message().c_str());
        s->endGesture();
    }
}
BENCHMARK(BM_PreviewedDragFinish)->Unit(benchmark::kMillisecond)->UseRealTime();

// The first coarse tile read after a drag step (what the editor's first tile worker pays): a level-2
// tile of 64^2 quads plus apron over the dragged point. The reference window is cached after the
// first iteration, so this is the edit's block means: a full rebuild of the extent's sums per edit
// before they were updated over the changed window.
static void BM_CoarseTileAfterDragStep(benchmark::State& state) {
    EditSession* s = session(state);
    if (!s) return;
    const EditId id = dragged(*s);
    int step = 0;
    s->beginGesture();
    for (auto _ : state) {
        state.PauseTiming();
        dragStep(state, *s, id, step++);
        const HeightSource source = s->heightSource();
        state.ResumeTiming();
        auto tile = source({128 - 1, 128 - 1, 67, 67}, 2);
        if (!tile) state.SkipWithError(tile.message().c_str());
        benchmark::DoNotOptimize(tile);
    }
    s->endGesture();
}
BENCHMARK(BM_CoarseTileAfterDragStep)->Iterations(40)->Unit(benchmark::kMillisecond)->UseRealTime();

// Undo of one drag step (the redo that re-applies it is not timed).
static void BM_UndoDragStep(benchmark::State& state) {
    EditSession* s = session(state);
    if (!s) return;
    const EditId id = dragged(*s);
    int step = 0;
    for (auto _ : state) {
        state.PauseTiming();
        auto moved = s->movePoint(id, 512 + 4.0 * (step++ % 5), 512);
        if (!moved) state.SkipWithError(moved.message().c_str());
        state.ResumeTiming();
        auto r = s->undo();
        if (!r) state.SkipWithError(r.message().c_str());
    }
}
BENCHMARK(BM_UndoDragStep)->Unit(benchmark::kMillisecond)->UseRealTime();

// heightAt inside the extent (resident): the game's collision and the editor's picks.
static void BM_HeightAtResident(benchmark::State& state) {
    EditSession* s = session(state);
    if (!s) return;
    const GridFrame f = s->frame();
    double x = 100.25, sum = 0.0;
    for (auto _ : state) {
        auto h = s->heightAt(f.worldX(x), f.worldY(300.5));
        sum += *h;
        x = x < 900.0 ? x + 0.37 : 100.25;
    }
    benchmark::DoNotOptimize(sum);
}
BENCHMARK(BM_HeightAtResident)->Unit(benchmark::kNanosecond);

// Memory: 100 undo steps of point edits (radius 64, spread over the extent), per extent pixel.
static void BM_UndoMemory100Steps(benchmark::State& state) {
    EditSession* s = session(state);
    if (!s) return;
    for (auto _ : state) {
        for (int i = 0; i < 100; ++i) {
            PointConstraint p;
            p.x = 96 + 83 * (i % 10), p.y = 96 + 83 * (i / 10), p.height_m = s->heights().at(512, 512), p.radius_px = 64;
            auto r = s->addPoint(p);
            if (!r) state.SkipWithError(r.message().c_str());
        }
    }
    const PixelWindow e = s->extent();
    state.counters["undo_bytes_per_pixel"] = static_cast<double>(s->undoBytes()) / (static_cast<double>(e.width) * e.height);
}
BENCHMARK(BM_UndoMemory100Steps)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
