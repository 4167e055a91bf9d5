// Recomposition speed of the layer stack (Bradbury et al. 2014 s3.2: "real-time reconstruction, even
// as the user changes the blending parameters"). Target: a 1024^2 stack of 8 layers recomposed
// after a weight change in at most 20 ms (median).
//
// Run: layers_bench --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdio>
#include <string>

#include "terrasynth/layers.h"

namespace {

using namespace terrasynth;

constexpr int kSize = 1024;
constexpr double kSpacing = 30.0;

EditLayer layer(ToolParams tool, const char* name) {
    EditLayer l;
    l.name = name;
    l.weights = defaultWeights(tool);
    l.tool = std::move(tool);
    return l;
}

NoiseParams fullFrameNoise(uint64_t seed) {
    NoiseParams n;
    n.fractal.seed = seed;
    n.fractal.amplitude_m = 40.0;
    n.fractal.wavelength_px = 128.0;
    n.fractal.octaves = 6;
    return n;
}

LayerStack baseStack() {
    LayerStack s;
    s.base.source = BaseSource::Fractal;
    s.base.fractal.seed = 7;
    s.base.fractal.amplitude_m = 800.0;
    return s;
}

// Worst case: every one of the 8 layers covers the whole grid.
LayerStack fullFrameStack() {
    LayerStack s = baseStack();
    for (int i = 0; i < 7; ++i) s.layers.push_back(layer(fullFrameNoise(100 + i), "noise"));
    return s;
}

// A typical editing session: tools of every kind, a pasted external DEM, fractal detail over all.
LayerStack mixedStack() {
    LayerStack s = baseStack();
    PeakParams peak;
    peak.center_x = 300, peak.center_y = 400, peak.height_m = 900, peak.spread_px = 60, peak.skewness = 0.3;
    s.layers.push_back(layer(peak, "peak"));
    RidgeParams ridge;
    ridge.points = {{100, 800}, {400, 700}, {700, 750}, {950, 600}};
    ridge.profile_m = {200, 700, 500};
    ridge.width_px = 40;
    s.layers.push_back(layer(ridge, "ridge"));
    PasteParams paste;
    paste.source = std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars/orom_himalaya-everest.png";
    paste.source_x = 100, paste.source_y = 100;
    paste.dest = Region{RegionShape::Ellipse, 500, 100, 400, 400};
    s.layers.push_back(layer(paste, "paste"));
    s.layers.push_back(layer(fullFrameNoise(5), "detail"));
    HoleFillParams hole;
    hole.hole = Region{RegionShape::Ellipse, 150, 150, 96, 96};
    s.layers.push_back(layer(hole, "hole"));
    PeakParams pit = peak;
    pit.center_x = 800, pit.center_y = 850, pit.height_m = -300, pit.kurtosis = -0.8, pit.skewness = 0;
    s.layers.push_back(layer(pit, "crater"));
    s.layers.push_back(layer(fullFrameNoise(6), "fine detail"));
    return s;
}

void recomposeAfterWeightChange(benchmark::State& state, LayerStack stack, int layer_index) {
    auto editor = LayerEditor::create(std::move(stack), Heightfield(kSize, kSize, kSpacing));
    if (!editor) {
        state.SkipWithError(editor.message().c_str());
        return;
    }
    if (auto warm = editor->heights(); !warm) {
        state.SkipWithError(warm.message().c_str());
        return;
    }
    float w = 0.5f;
    for (auto _ : state) {
        BandWeights weights = editor->stack().layers[layer_index].weights;
        weights.high = w;
        w = w == 0.5f ? 1.5f : 0.5f;
        editor->setWeights(layer_index, weights);
        auto h = editor->currentHeights();
        benchmark::DoNotOptimize((*h)->heights.data());
    }
    state.counters["layers"] = 8;
}

void BM_RecomposeAfterWeightChange_FullFrame8(benchmark::State& state) {
    recomposeAfterWeightChange(state, fullFrameStack(), 6);
}
void BM_RecomposeAfterWeightChange_Mixed8(benchmark::State& state) {
    recomposeAfterWeightChange(state, mixedStack(), 6);
}
// Weight change below the paste and hole fill: those two read the terrain below and are rebuilt.
void BM_RebuildAfterWeightChangeBelowTerrainReaders_Mixed8(benchmark::State& state) {
    recomposeAfterWeightChange(state, mixedStack(), 0);
}
void BM_ApplyLayerStackFromScratch_Mixed8(benchmark::State& state) {
    const LayerStack stack = mixedStack();
    const Heightfield grid(kSize, kSize, kSpacing);
    for (auto _ : state) {
        auto h = applyLayerStack(stack, grid);
        if (!h) state.SkipWithError(h.message().c_str());
        benchmark::DoNotOptimize(h);
    }
}

BENCHMARK(BM_RecomposeAfterWeightChange_FullFrame8)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_RecomposeAfterWeightChange_Mixed8)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(BM_RebuildAfterWeightChangeBelowTerrainReaders_Mixed8)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_ApplyLayerStackFromScratch_Mixed8)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
