// Median time to build the exemplar database (Gain et al. 2015 s4) from real DEMs: all 17 shared
// exemplars (the target: under 60 s on 2 cores) and the shipped default set in data/exemplars.
// One build per repetition (a build is seconds long); run with e.g.
//   db_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// Counters: bytes_per_base_pixel (database memory / level-0 exemplar pixels; paper budget 42.7),
// base_pixels, levels, and the seconds spent reading+resampling and on each pyramid level.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <string>

#include "terrasynth/database.h"

using namespace terrasynth;

namespace {

using Clock = std::chrono::steady_clock;

// Seconds between consecutive progress reports: "level i" is reported when level i is finished.
struct StageTimer {
    Clock::time_point last = Clock::now();
    double preparation_s = 0.0;          // reading, resampling, until level 0 starts
    std::map<int, double> level_s;      // by level number (levels may be built in any order)

    void onProgress(const std::string& name, double) {
        const Clock::time_point now = Clock::now();
        const double elapsed = std::chrono::duration<double>(now - last).count();
        last = now;
        if (name.rfind("level ", 0) == 0)
            level_s[std::atoi(name.c_str() + 6)] += elapsed;
        else
            preparation_s += elapsed;
    }
};

void buildAndReport(benchmark::State& state, const std::string& directory) {
    std::shared_ptr<const ExemplarDatabase> db;
    StageTimer timer;
    for (auto _ : state) {
        timer = StageTimer();
        DatabaseBuildOptions options;  // defaults: 6 levels, all hardware threads
        options.progress = [&timer](const std::string& stage, double progress) { timer.onProgress(stage, progress); };
        auto built = buildDatabase(std::vector<std::string>{directory}, options);
        if (!built) {
            state.SkipWithError(built.message().c_str());
            return;
        }
        db = built.value();
    }
    state.counters["bytes_per_base_pixel"] = db->bytesPerBasePixel();
    state.counters["base_pixels"] = static_cast<double>(db->basePixelCount());
    state.counters["exemplars"] = static_cast<double>(db->exemplars.size());
    state.counters["levels"] = db->levelCount();
    state.counters["prep_s"] = timer.preparation_s;
    for (const auto& [level, seconds] : timer.level_s) state.counters["level" + std::to_string(level) + "_s"] = seconds;
}

void BM_BuildDatabase_SharedExemplars(benchmark::State& state) {
    buildAndReport(state, TERRASYNTH_BENCH_SHARED_EXEMPLARS);
}
BENCHMARK(BM_BuildDatabase_SharedExemplars)->Iterations(1)->Repetitions(3)->UseRealTime()->Unit(benchmark::kSecond);

void BM_BuildDatabase_ShippedDefaults(benchmark::State& state) {
    buildAndReport(state, std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars");
}
BENCHMARK(BM_BuildDatabase_ShippedDefaults)->Iterations(1)->Repetitions(3)->UseRealTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
