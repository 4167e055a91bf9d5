// Proposed bench/stats_bench.cpp: median time of the realism statistics on real 1024^2 and 512^2 DEMs.
#include <benchmark/benchmark.h>

#include <string>

#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain_stats.h"

using namespace terrasynth;

namespace {
Heightfield field(int size) {
    auto e = readExemplar(std::string(TERRASYNTH_BENCH_SHARED_EXEMPLARS) + "/glac_sthelens_10m.png");
    if (!e) return Heightfield(size, size, 10.0);
    Heightfield out(size, size, e->field.meters_per_pixel_x);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) out.at(x, y) = e->field.at(x + 400, y + 400);
    return out;
}

void BM_ComputeTerrainStats(benchmark::State& state) {
    const Heightfield f = field(static_cast<int>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(computeTerrainStats(f));
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(f.size()));
}
BENCHMARK(BM_ComputeTerrainStats)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond);

void BM_DrainageArea(benchmark::State& state) {
    const Heightfield f = field(1024);
    for (auto _ : state) benchmark::DoNotOptimize(drainageArea(f));
}
BENCHMARK(BM_DrainageArea)->Unit(benchmark::kMillisecond);

void BM_PowerSpectrum(benchmark::State& state) {
    const Heightfield f = field(1024);
    for (auto _ : state) benchmark::DoNotOptimize(powerSpectrum(f));
}
BENCHMARK(BM_PowerSpectrum)->Unit(benchmark::kMillisecond);

void BM_FillDepressions(benchmark::State& state) {
    const Heightfield f = field(1024);
    for (auto _ : state) benchmark::DoNotOptimize(fillDepressions(f, state.range(0) != 0));
}
BENCHMARK(BM_FillDepressions)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
