// Local edit on a 1024^2 terrain (issue target: <= 33 ms median for a point constraint of radius 64).
// Run: build/bin/incremental_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "terrasynth/incremental.h"

using namespace terrasynth;

// state.range(0): 1 = lift the point so its site lands on its height (the default), 0 = the paper's
// plain target.
static void BM_PointEditRadius64On1024(benchmark::State& state) {
    ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
    auto db = loadOrBuildDatabase({std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars"}, {},
                                  std::string(TERRASYNTH_BENCH_POCL_CACHE) + "/../bench_default.tsdb");
    if (!db) return state.SkipWithError(db.message().c_str());
    auto s = Synthesizer::create(db.value());
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
BENCHMARK(BM_PointEditRadius64On1024)->ArgName("hold")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
