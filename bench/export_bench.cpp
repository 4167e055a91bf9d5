// Export speed and size: a 4096^2 terrain (a real DEM upsampled to 4096^2) to GLB with 4 LODs in
// 256-quad tiles, plain and quantized, and the mesher alone on one 256-quad tile.
// Run: export_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Counters: file_MB (bytes written), and for the quantized run size_ratio = quantized / plain.
#include <benchmark/benchmark.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/mesh.h"

using namespace terrasynth;

namespace {

const Heightfield& terrain4096() {
    static const Heightfield field = [] {
        auto exemplar = readExemplar(std::string(TERRASYNTH_BENCH_DATA_DIR) + "/exemplars/orom_alaska.png");
        if (!exemplar) {
            std::fprintf(stderr, "%s\n", exemplar.message().c_str());
            std::exit(1);
        }
        const Heightfield& f = exemplar->field;
        Heightfield big = resampleToSpacing(f, f.meters_per_pixel_x * f.width / 4096.0);
        if (big.width != 4096 || big.height != 4096) {  // rounding: pad or crop to exactly 4096^2
            Heightfield exact(4096, 4096, big.meters_per_pixel_x);
            for (int y = 0; y < 4096; ++y)
                for (int x = 0; x < 4096; ++x) exact.at(x, y) = big.clamped(x, y);
            big = std::move(exact);
        }
        return big;
    }();
    return field;
}

std::string outputPath(const char* name) {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/terrasynth_bench_" + std::to_string(::getpid()) + "_" + name;
}

double plain_bytes = 0.0;

void exportOnce(benchmark::State& state, bool quantize) {
    const HeightSource source = heightSourceFromField(terrain4096());
    GltfExportOptions options;
    options.region = {0, 0, 4096, 4096};
    options.tile_size = 256;
    options.lods = 4;
    options.lod_layout = LodLayout::MsftLod;  // one file, as the README's figures measured
    options.quantize = quantize;
    const std::string path = outputPath(quantize ? "q.glb" : "plain.glb");
    GltfExportStats stats;
    for (auto _ : state) {
        auto result = exportGltf(path, source, options);
        if (!result) {
            state.SkipWithError(result.message().c_str());
            break;
        }
        stats = *result;
    }
    std::remove(path.c_str());
    state.counters["file_MB"] = stats.file_bytes / 1e6;
    state.counters["lod0_triangles_M"] = stats.lods.empty() ? 0.0 : stats.lods[0].triangles / 1e6;
    if (!quantize) plain_bytes = double(stats.file_bytes);
    if (quantize && plain_bytes > 0) state.counters["size_ratio"] = stats.file_bytes / plain_bytes;
}

void BM_Export4096Lods4(benchmark::State& state) { exportOnce(state, false); }
void BM_Export4096Lods4Quantized(benchmark::State& state) { exportOnce(state, true); }

void BM_MeshTile256(benchmark::State& state) {
    Heightfield tile(259, 259, terrain4096().meters_per_pixel_x);
    for (int y = 0; y < 259; ++y)
        for (int x = 0; x < 259; ++x) tile.at(x, y) = terrain4096().at(1000 + x, 1000 + y);
    MeshOptions options;
    options.border = 1;
    options.full_res_border = true;
    options.step = lodStep(static_cast<int>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(meshHeightfield(tile, options));
}

}  // namespace

BENCHMARK(BM_Export4096Lods4)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_Export4096Lods4Quantized)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_MeshTile256)->Arg(0)->Arg(3)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
