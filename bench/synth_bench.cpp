// Synthesis speed (issue targets: 512^2 <= 100 ms, 1024^2 <= 400 ms on the 2-core CPU via PoCL;
// paper: 63 ms / 165 ms on a 2012 GPU) and memory per synthesized pixel (paper: 84 bytes).
// Run: build/bin/synth_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "terrasynth/synthesizer.h"

using namespace terrasynth;

namespace {

std::shared_ptr<const ExemplarDatabase> database() {
    static std::shared_ptr<const ExemplarDatabase> db = [] {
        ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
        auto loaded = loadOrBuildDatabase({std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars"}, {},
                                          std::string(TERRASYNTH_BENCH_POCL_CACHE) + "/../bench_default.tsdb");
        if (!loaded) {
            std::fprintf(stderr, "%s\n", loaded.message().c_str());
            std::exit(1);
        }
        return loaded.value();
    }();
    return db;
}

Synthesizer& synthesizer(SynthesisBackend backend) {
    static std::unique_ptr<Synthesizer> cl, ref;
    auto& slot = backend == SynthesisBackend::OpenCL ? cl : ref;
    if (!slot) {
        SynthesizerOptions options;
        options.backend = backend;
        auto s = Synthesizer::create(database(), options);
        if (!s) {
            std::fprintf(stderr, "%s\n", s.message().c_str());
            std::exit(1);
        }
        slot = std::move(s.value());
    }
    return *slot;
}

void synthesize(benchmark::State& state, SynthesisBackend backend, Drainage drainage = SynthesisParams{}.drainage) {
    const int size = static_cast<int>(state.range(0));
    Synthesizer& s = synthesizer(backend);
    SynthesisParams params;
    params.drainage = drainage;
    int64_t tile = 0;
    s.synthesize({0, 0, size, size}, params, 0, false);  // warm-up: kernel build, buffer allocation
    for (auto _ : state) {
        // A new window each iteration (as when streaming tiles), never a cached result.
        auto out = s.synthesize({tile * size, 0, size, size}, params, 0, false);
        if (!out) state.SkipWithError(out.message().c_str());
        benchmark::DoNotOptimize(out);
        ++tile;
    }
    state.counters["bytes_per_pixel"] = s.lastBytesPerPixel();
    state.counters["Mpixel_per_s"] =
        benchmark::Counter(static_cast<double>(size) * size, benchmark::Counter::kIsIterationInvariantRate);
}

// The default settings: drainage by breaching.
void BM_SynthesizeOpenCL(benchmark::State& state) { synthesize(state, SynthesisBackend::OpenCL); }
void BM_SynthesizeReference(benchmark::State& state) { synthesize(state, SynthesisBackend::Reference); }
// Without the drainage step, to see its cost next to BM_SynthesizeOpenCL.
void BM_SynthesizeOpenCLOff(benchmark::State& state) { synthesize(state, SynthesisBackend::OpenCL, Drainage::Off); }

// The drainage's cost (breach over off, "same run"): each iteration synthesizes one window with
// drainage off and the next with breach, the order alternating, so both see the same minutes of a
// shared machine, whose speed drifts by 20% and more between runs of a few seconds
// (docs/benchmarks.md, "Drainage cost"). Reports the medians of each and the median of the pairs'
// own ratios; the iteration time is the pair's. At 4096^2 for a GPU, where the margins' share is
// smaller and the breach's searches are more (about a minute on 2 CPU cores).
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Interleaved rounds of the default with drainage off and of `params`, on fresh windows: the medians
// of each and of their per-round ratio (machines and loads differ 2x; a ratio within a round does not).
void overOff(benchmark::State& state, const SynthesisParams& params, const char* name) {
    const int size = static_cast<int>(state.range(0));
    Synthesizer& s = synthesizer(SynthesisBackend::OpenCL);
    SynthesisParams off;
    off.drainage = Drainage::Off;
    s.synthesize({0, 0, size, size}, off, 0, false);  // warm-up, as in synthesize()
    s.synthesize({0, 0, size, size}, params, 0, false);
    std::vector<double> off_ms, on_ms, ratios;
    int64_t tile = 0;
    auto timed = [&](const SynthesisParams& p) {
        const auto start = std::chrono::steady_clock::now();
        auto out = s.synthesize({tile++ * size, 0, size, size}, p, 0, false);
        if (!out) state.SkipWithError(out.message().c_str());
        benchmark::DoNotOptimize(out);
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    };
    for (auto _ : state) {
        const bool off_first = off_ms.size() % 2 == 0;
        const double first = timed(off_first ? off : params), second = timed(off_first ? params : off);
        off_ms.push_back(off_first ? first : second);
        on_ms.push_back(off_first ? second : first);
        ratios.push_back(on_ms.back() / off_ms.back());
    }
    state.counters["off_ms"] = median(off_ms);
    state.counters[std::string(name) + "_ms"] = median(on_ms);
    state.counters[std::string(name) + "_over_off"] = median(ratios);
}

void BM_BreachOverOff(benchmark::State& state) {
    SynthesisParams breach;
    breach.drainage = Drainage::Breach;
    overOff(state, breach, "breach");
}

// Breach with the offset relaxation (SynthesisParams::relax_offsets) against drainage off.
void BM_BreachRelaxedOverOff(benchmark::State& state) {
    SynthesisParams relaxed;
    relaxed.drainage = Drainage::Breach;
    relaxed.relax_offsets = true;
    overOff(state, relaxed, "relaxed");
}

void BM_LiftPoints(benchmark::State& state) {
    const int count = static_cast<int>(state.range(0)), size = static_cast<int>(state.range(1));
    auto constraints = std::make_shared<SynthesisConstraints>();
    uint32_t h = 12345;
    auto next = [&] { return (h = h * 1664525u + 1013904223u) / 4294967296.0; };
    for (int i = 0; i < count; ++i) {
        PointConstraint p;
        p.x = 8 + (size - 16) * next(), p.y = 8 + (size - 16) * next();
        p.height_m = static_cast<float>(1500 + 1000 * next());
        p.radius_px = 32.0f;
        constraints->points.push_back(p);
    }
    SynthesisParams params;
    params.constraints = constraints;
    Synthesizer& s = synthesizer(SynthesisBackend::OpenCL);
    for (auto _ : state) {
        auto lifted = liftPointConstraints(s, params);
        if (!lifted) state.SkipWithError(lifted.message().c_str());
        benchmark::DoNotOptimize(lifted);
    }
}

}  // namespace

BENCHMARK(BM_SynthesizeOpenCL)->Arg(256)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SynthesizeOpenCLOff)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BreachOverOff)->Arg(1024)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BreachOverOff)->Arg(4096)->Iterations(4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BreachRelaxedOverOff)->Arg(1024)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SynthesizeReference)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_LiftPoints)->Args({100, 256})->Args({1000, 1024})->Args({10000, 1024})->Unit(benchmark::kMillisecond)
    ->UseRealTime()->Iterations(1);

BENCHMARK_MAIN();
