// Tile pipeline throughput and main-thread merge cost (issue 6 targets):
//  - BM_TileThroughput: tiles of 256^2 quads (heights + mesh + detached OSG node) per second on a pool
//    of 2 worker threads; target >= 20/s. Sources: the synthesized Terrain, and a mirrored real DEM
//    (isolates meshing and OSG cost).
//  - BM_FlightMerge/<metres>: a paced headless flight (UPDATE + CULL every frame, workers paging 256^2
//    tiles); counters give the per-frame merge time (median, max; target max <= 4 ms), the tile cache
//    and the process RSS (bounded: the 200 km flight must not need more than the 10 km one).
// Run: tiles_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "headless_view.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain.h"
#include "terrasynth_plugin/terrain_node.h"
#include "tile_builder.h"
#include "worker_pool.h"

namespace {

using namespace terrasynth;
using namespace terrasynth::plugin;
using terrasynth::test::HeadlessView;

struct Dem {
    Heightfield field;
    HeightSource source;
};

const Dem& dem() {
    static const Dem d = [] {
        ::setenv("POCL_CACHE_DIR", TERRASYNTH_BENCH_POCL_CACHE, 0);
        auto e = readExemplar(std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars/orom_alaska.png");
        if (!e) {
            std::fprintf(stderr, "tiles_bench: %s\n", e.message().c_str());
            std::exit(1);
        }
        return Dem{e->field, mirroredExemplarSource(e->field)};
    }();
    return d;
}

// One iteration = 8 level-0 tiles (the 4 children of 2 level-1 parents) built on a pool of 2 workers,
// as the manager builds them: geomorph targets from the resident parent (parents built untimed).
void throughput(benchmark::State& state, const HeightSource& source, double mpp) {
    TileBuildSettings s;  // the plugin's defaults: geomorphing on, under a level-5 root
    s.layout = {256, mpp};
    s.geomorph = true;
    s.max_level = 5;
    int64_t offset = 0;
    int failures = 0;
    for (auto _ : state) {
        state.PauseTiming();
        std::vector<std::pair<TileKey, std::shared_ptr<const TileData>>> jobs;
        for (int p = 0; p < 2; ++p) {
            const TileKey parent{1, offset + p, 7};  // fresh tiles every iteration: no cache can help
            const TileBuild built = buildTile(source, parent, s);
            failures += !built.status;
            if (!built.status) continue;
            for (int c = 0; c < 4; ++c) jobs.emplace_back(parent.child(c % 2, c / 2), built.data);
        }
        offset += 2;
        state.ResumeTiming();
        WorkerPool pool(2);
        std::atomic<int> failed{0};
        for (const auto& job : jobs)
            pool.push({0.0, [&] { failed += !buildTile(source, job.first, s, job.second.get()).status; }});
        pool.waitIdle();
        failures += failed;
    }
    if (failures) state.SkipWithError("tile builds failed");
    state.SetItemsProcessed(state.iterations() * 8);
    state.counters["tiles_per_s"] = benchmark::Counter(double(state.iterations() * 8), benchmark::Counter::kIsRate);
}

void BM_TileThroughput_Dem(benchmark::State& state) { throughput(state, dem().source, dem().field.meters_per_pixel_x); }
BENCHMARK(BM_TileThroughput_Dem)->Unit(benchmark::kMillisecond)->UseRealTime();

// A project over the shipped exemplars, with its database cached in the build tree.
std::shared_ptr<Terrain> benchTerrain() {
    static std::shared_ptr<Terrain> terrain = [] {
        Project p;
        for (const char* stem : {"orom_alaska", "orom_rockies"})
            p.exemplars.push_back(std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars/" + stem + ".png");
        p.database = std::string(TERRASYNTH_BENCH_POCL_CACHE) + "/../tiles_bench.tsdb";
        auto t = Terrain::fromProject(p);
        if (!t) {
            std::fprintf(stderr, "tiles_bench: %s\n", t.message().c_str());
            return std::shared_ptr<Terrain>();
        }
        return *t;
    }();
    return terrain;
}

void BM_TileThroughput_Terrain(benchmark::State& state) {
    auto terrain = benchTerrain();
    if (!terrain) {
        state.SkipWithError("no terrain");
        return;
    }
    throughput(state, [terrain](const PixelWindow& w, int level) { return terrain->heights(w, level); },
               terrain->metersPerPixel(0));
}
BENCHMARK(BM_TileThroughput_Terrain)->Unit(benchmark::kMillisecond)->UseRealTime();

size_t residentMb() {
    long pages = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return static_cast<size_t>(resident) * static_cast<size_t>(sysconf(_SC_PAGESIZE)) / (1024 * 1024);
}

// state.range(0) metres in 2400 frames paced at 60 frames/s (40 s; 10 km = 250 m/s) at 2.5 km,
// looking ahead and down.
void flight(benchmark::State& state, const HeightSource& source, double mpp) {
    const double distance = static_cast<double>(state.range(0));
    double median = 0, worst = 0, mean_frame_ms = 0;
    size_t rss_max = 0, resident_max = 0;
    uint64_t built = 0;
    double build_ms = 0, heights_ms = 0;
    for (auto _ : state) {
        TerrainNodeOptions o;
        o.tile_size = 256;
        o.max_level = 4;
        o.threads = 2;
        o.cache_mb = 256;
        osg::ref_ptr<TerrainNode> node = new TerrainNode(source, mpp, o);
        HeadlessView view(node.get());
        const int frames = 2400;
        const auto t0 = std::chrono::steady_clock::now();
        for (int f = 0; f < frames; ++f) {
            const double x = distance * f / frames;
            const osg::Vec3d eye(x, -20000 - 0.3 * x, 2500), center(x + 3000, -20000 - 0.3 * x - 900, 1200);
            view.frame(eye, center);
            // Pace like a 60 Hz display would (the workers get the time between frames).
            std::this_thread::sleep_until(t0 + std::chrono::microseconds(16667) * (f + 1));
            resident_max = std::max(resident_max, node->stats().resident_bytes);
            if (f % 60 == 0) rss_max = std::max(rss_max, residentMb());
        }
        mean_frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / frames;
        std::vector<double> merges = node->mergeTimesMs();
        std::sort(merges.begin(), merges.end());
        median = merges.empty() ? 0.0 : merges[merges.size() / 2];
        worst = merges.empty() ? 0.0 : merges.back();
        built = node->stats().tiles_built;
        build_ms = node->stats().mean_build_ms;
        heights_ms = node->stats().mean_heights_ms;
    }
    state.counters["merge_ms_median"] = median;
    state.counters["merge_ms_max"] = worst;
    state.counters["frame_ms"] = mean_frame_ms;
    state.counters["tiles_built"] = double(built);
    state.counters["build_ms_mean"] = build_ms;
    state.counters["heights_ms_mean"] = heights_ms;
    state.counters["tile_cache_mb_max"] = double(resident_max) / (1024 * 1024);
    state.counters["rss_mb_max"] = double(rss_max);
}
void BM_FlightMerge_Dem(benchmark::State& state) { flight(state, dem().source, dem().field.meters_per_pixel_x); }
BENCHMARK(BM_FlightMerge_Dem)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)->Arg(10000)->Arg(200000);

void BM_FlightMerge_Terrain(benchmark::State& state) {
    auto terrain = benchTerrain();
    if (!terrain) {
        state.SkipWithError("no terrain");
        return;
    }
    flight(state, [terrain](const PixelWindow& w, int level) { return terrain->heights(w, level); },
           terrain->metersPerPixel(0));
}
BENCHMARK(BM_FlightMerge_Terrain)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)->Arg(10000);

}  // namespace

// TerrainNode::heightAt (issue 15 target: <= 50 us): the finest resident tile's data at a random
// point, with 24 level-0 tiles and their coarser levels resident.
void BM_HeightAt(benchmark::State& state) {
    TerrainNodeOptions o;
    o.threads = 2;
    osg::ref_ptr<TerrainNode> node = new TerrainNode(dem().source, dem().field.meters_per_pixel_x, o);
    const PixelWindow region{0, 0, 6 * 256, 4 * 256};
    for (int level : {5, 2, 0})
        if (Status st = node->preload(region, level); !st) state.SkipWithError(st.message().c_str());
    const double mpp = dem().field.meters_per_pixel_x;
    uint64_t rng = 88172645463325252ull;
    size_t answered = 0;
    for (auto _ : state) {
        rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
        const double u = static_cast<double>(rng % 1000000) * 1e-6, v = static_cast<double>((rng >> 20) % 1000000) * 1e-6;
        const double x = u * region.width * mpp, y = -v * region.height * mpp;
        const std::optional<float> h = node->heightAt(x, y);
        answered += h.has_value();
        benchmark::DoNotOptimize(h);
    }
    state.counters["answered"] = static_cast<double>(answered) / std::max<int64_t>(1, state.iterations());
}
BENCHMARK(BM_HeightAt)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
