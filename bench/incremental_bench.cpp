// Local edits on a 1024^2 terrain (issue targets: <= 33 ms median for a point constraint of radius 64,
// <= 60 ms for a curve widget).
// Run: build/bin/incremental_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "terrasynth/curve_course.h"
#include "terrasynth/incremental.h"

using namespace terrasynth;

// The synthesizer of the shipped default exemplars (database cached in the build folder), or an
// error message.
static Result<std::unique_ptr<Synthesizer>> defaultSynthesizer() {
    ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
    auto db = loadOrBuildDatabase({std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars"}, {},
                                  std::string(TERRASYNTH_BENCH_POCL_CACHE) + "/../bench_default.tsdb");
    if (!db) return db.status();
    return Synthesizer::create(db.value());
}

// state.range(0): 1 = lift the point so its site lands on its height (the default), 0 = the paper's
// plain target.
static void BM_PointEditRadius64On1024(benchmark::State& state) {
    auto s = defaultSynthesizer();
    if (!s) return state.SkipWithError(s.message().c_str());
    auto terrain = IncrementalTerrain::create(*s.value(), {0, 0, 1024, 1024}, SynthesisParams{});
    if (!terrain) return state.SkipWithError(terrain.message().c_str());
    terrain->holdPointHeights(state.range(0) != 0);
    const float base = terrain->heights().at(512, 512);
    int edit = 0;
    for (auto _ : state) {
        // Drag the constraint's height up and down, as a user would with the widget.
        auto c = std::make_shared<SynthesisConstraints>();
        c->points.push_back({512.0, 512.0, base + 100.0f * static_cast<float>(edit++ % 7), 0.0f, 0.0f, 64.0f});
        Status st = terrain->update(c, {512 - 64, 512 - 64, 129, 129});
        if (!st) state.SkipWithError(st.message().c_str());
    }
    const PixelWindow w = terrain->lastWindow();
    state.counters["window_pixels"] = static_cast<double>(w.width) * w.height;
    const PointConstraint& p = terrain->params().constraints->points[0];
    state.counters["site_error_m"] = std::fabs(terrain->heights().at(512, 512) - p.height_m);
}
BENCHMARK(BM_PointEditRadius64On1024)
    ->ArgName("hold")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// A curve constraint's widget dragged up and down on a 1024^2 terrain, as projects synthesize it
// (hold_point_heights: courses held on the free levels, lift profiles). The course (about 260 px, a
// spline through 3 points) stays put, so every edit keeps the curve's lift profile as its start.
// state.range(0): 1 = lift the profile (the default), 0 = keep it as it is.
static void BM_CurveWidgetEditOn1024(benchmark::State& state) {
    auto s = defaultSynthesizer();
    if (!s) return state.SkipWithError(s.message().c_str());
    SynthesisParams params;
    params.hold_on_free_levels = true;
    auto terrain = IncrementalTerrain::create(*s.value(), {0, 0, 1024, 1024}, params);
    if (!terrain) return state.SkipWithError(terrain.message().c_str());
    const float base = terrain->heights().at(512, 480);
    auto curveAt = [&](float raise) {
        auto c = std::make_shared<SynthesisConstraints>();
        CurveConstraint curve;
        curve.course = {{400.0, 500.0}, {512.0, 470.0}, {630.0, 520.0}};
        for (double t : {0.0, 0.5, 1.0}) {
            CurveWidget w;
            w.t = t;
            w.height_m = base + (t == 0.5 ? raise : 0.0f);
            w.left_gradient = -0.15f, w.right_gradient = -0.2f;
            w.left_reach_px = w.right_reach_px = 40.0f;
            curve.widgets.push_back(w);
        }
        c->curves.push_back(curve);
        return c;
    };
    if (Status st = terrain->applyEdit(curveAt(0.0f)); !st) return state.SkipWithError(st.message().c_str());
    terrain->holdPointHeights(state.range(0) != 0);
    int edit = 0;
    for (auto _ : state) {
        Status st = terrain->applyEdit(curveAt(60.0f * static_cast<float>(edit++ % 7)));
        if (!st) state.SkipWithError(st.message().c_str());
    }
    const PixelWindow w = terrain->lastWindow();
    state.counters["window_pixels"] = static_cast<double>(w.width) * w.height;
    const CurveHold hold = measureCurveHold(terrain->heights(), 0, 0, terrain->params().constraints->curves, 0,
                                            s.value()->database().meters_per_pixel);
    std::vector<float> errors = hold.height_error_m;
    for (float& e : errors) e = std::fabs(e);
    std::sort(errors.begin(), errors.end());
    state.counters["course_median_error_m"] = errors.empty() ? 0.0 : errors[errors.size() / 2];
}
BENCHMARK(BM_CurveWidgetEditOn1024)
    ->ArgName("lift")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

BENCHMARK_MAIN();
