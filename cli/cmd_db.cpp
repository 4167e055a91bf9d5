// terrasynth db build <exemplar files or dirs> -o db.tsdb [--levels N] [--meters-per-pixel M]
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "command_registry.h"
#include "terrasynth_flags/flag_checks.h"
#include "outputs.h"
#include "terrasynth/database.h"

namespace terrasynth::cli {
namespace {

struct DbBuildArgs {
    std::vector<std::string> inputs;
    std::string output;
    int levels = 6;
    double meters_per_pixel = 0.0;
    int threads = 0;
    bool quiet = false;
};

void runDbBuild(const DbBuildArgs& args) {
    // Refuse an unwritable output before spending minutes on the build.
    if (Status s = checkOutputs({{"-o", args.output}}); !s) return fail("db build", s.message());
    DatabaseBuildOptions options;
    options.levels = args.levels;
    options.meters_per_pixel = args.meters_per_pixel;
    options.threads = args.threads;
    std::string last_stage;
    if (!args.quiet)
        options.progress = [&](const std::string& stage, double progress) {
            if (stage != last_stage && !last_stage.empty()) std::fprintf(stderr, "\n");
            last_stage = stage;
            std::fprintf(stderr, "\r  %-12s %3.0f%%", stage.c_str(), progress * 100.0);
            std::fflush(stderr);
        };
    std::vector<std::string> void_lines;  // printed after the progress lines
    options.on_voids = [&](const ExemplarInfo& exemplar, double share) {
        char line[64];
        std::snprintf(line, sizeof line, ": %.1f%% voids (NoData), never copied", 100.0 * share);
        void_lines.push_back(exemplar.path + line);
    };
    const auto start = std::chrono::steady_clock::now();
    auto db = buildDatabase(args.inputs, options);
    if (!args.quiet) std::fprintf(stderr, "\n");
    if (!db) return fail("db build", db.message());
    Status saved = saveDatabase(*db.value(), args.output);
    if (!saved) return fail("db build", saved.message());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const ExemplarDatabase& d = *db.value();
    std::printf("wrote %s: %zu exemplars, %zu types, %d levels, %.3f m/pixel\n", args.output.c_str(),
                d.exemplars.size(), d.type_names.size(), d.levelCount(), d.meters_per_pixel);
    for (const std::string& line : void_lines) std::printf("%s\n", line.c_str());
    std::printf("memory: %zu bytes for %zu base pixels = %.2f bytes per base pixel (paper: 42.67)\n",
                d.memoryBytes(), d.basePixelCount(), d.bytesPerBasePixel());
    std::printf("built in %.2f s\n", seconds);
}

void addDbCommand(CLI::App& app) {
    auto* db = app.add_subcommand("db", "Exemplar database (paper s4)");
    db->require_subcommand(1);
    auto args = std::make_shared<DbBuildArgs>();
    auto* build = db->add_subcommand("build", "Build a database from exemplar files or folders");
    build->add_option("inputs", args->inputs, "Exemplar files (PNG+JSON, F32+JSON, or any GDAL raster: .tif, .hgt, .asc, .vrt) or folders")->required();
    build->add_option("-o,--output", args->output, "Database file to write (.tsdb)")->required();
    build->add_option("--levels", args->levels, "Coarsest pyramid level L (levels 0..L)")->check(flags::FiniteRange(ranges::kDatabaseLevels));
    build->add_option("--meters-per-pixel", args->meters_per_pixel,
                      "Common spacing; default: the coarsest exemplar's")->check(flags::FiniteRange(ranges::kDatabaseSpacing));
    build->add_option("--threads", args->threads, "Worker threads (0 = all cores)")->check(flags::FiniteRange(ranges::kThreads));
    build->add_flag("-q,--quiet", args->quiet, "No progress output");
    setAction(build, [args] { runDbBuild(*args); });
}

const CommandRegistration kRegistration{"db", 10, addDbCommand};

}  // namespace
}  // namespace terrasynth::cli
