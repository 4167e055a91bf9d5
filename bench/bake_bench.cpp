// Tileset bake speed and size (issue 19 targets): the shipped default project synthesized and baked
// into 256-quad tiles with 4 LODs, in one process on all cores, plain and quantized.
//   BM_Bake/4096: a 4096^2 region (target <= 15 s on 2 cores); BM_Bake/2048: a 2048^2 region.
// Counters: tiles_per_s (tiles of all LODs), MB, bytes_per_km2, cpu_s (process CPU time, less noisy
// on a shared machine than wall time). Scaling over shard processes: scripts/bench-bake-scaling.sh.
// Run: bake_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "terrasynth/gltf_export.h"
#include "terrasynth/terrain.h"
#include "terrasynth/tileset_bake.h"

using namespace terrasynth;

namespace {

std::shared_ptr<Terrain> terrain() {
    static std::shared_ptr<Terrain> t = [] {
        ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
        auto opened = Terrain::open(std::string(TERRASYNTH_BENCH_DATA_DIR) + "/default.tsyn");
        if (!opened) {
            std::fprintf(stderr, "bake_bench: %s\n", opened.message().c_str());
            std::exit(1);
        }
        return *opened;
    }();
    return t;
}

double cpuSeconds() {
    rusage u;
    ::getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void bake(benchmark::State& state, bool quantize) {
    const int side = static_cast<int>(state.range(0));
    const std::shared_ptr<Terrain> t = terrain();
    BakeOptions o;
    o.region = {0, 0, side, side};
    o.tile_size = 256;
    o.levels = 4;
    o.quantize = quantize;
    o.meters_per_pixel = t->metersPerPixel(0);
    o.max_source_level = t->database().levelCount() - 1;
    o.source_id = "bench";
    const BakeSource source = [t](const PixelWindow& w, int level, bool) -> Result<BakeSamples> {
        auto h = t->heights(w, level);
        if (!h) return h.status();
        return BakeSamples{std::move(*h), {}};
    };
    const char* tmp = std::getenv("TMPDIR");
    const std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/terrasynth_bake_bench_" + std::to_string(::getpid());
    int64_t tiles = 0, bytes = 0;
    double cpu = 0.0;
    for (auto _ : state) {
        std::filesystem::remove_all(dir);
        const double cpu0 = cpuSeconds();
        Status s = prepareBakeFolder(dir, o);
        auto stats = s ? bakeTiles(dir, source, o) : Result<BakeStats>(s);
        auto merged = stats ? mergeTileset(dir) : Result<MergeStats>(stats.status());
        if (!merged) {
            state.SkipWithError(merged.message().c_str());
            break;
        }
        cpu = cpuSeconds() - cpu0;
        tiles = merged->tiles;
        bytes = merged->content_bytes;
    }
    std::filesystem::remove_all(dir);
    const double km2 = std::pow((side - 1) * o.meters_per_pixel / 1000.0, 2);
    state.counters["tiles_per_s"] = benchmark::Counter(double(tiles), benchmark::Counter::kIsRate);
    state.counters["MB"] = bytes / 1e6;
    state.counters["bytes_per_km2"] = bytes / km2;
    state.counters["cpu_s"] = cpu;
}

void BM_Bake(benchmark::State& state) { bake(state, false); }
void BM_BakeQuantized(benchmark::State& state) { bake(state, true); }

}  // namespace

BENCHMARK(BM_Bake)->Arg(2048)->Arg(4096)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_BakeQuantized)->Arg(4096)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK_MAIN();
