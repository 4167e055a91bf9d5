// `terrasynth bake <project.tsyn> -o world/ [--region X,Y,W,H] [--tile 256] [--levels 4] [--quantize]
//   [--tileset auto|explicit|implicit] [--heightmaps png|f32|tif] [--masks] [--shard I/N] [--threads N]
//   [--progress auto|bar|lines|none] [--prepare]`
// `terrasynth bake --merge world/`
// A 3D Tiles 1.1 tileset of glTF tiles, baked whole or one shard at a time (docs/bake.md). Exit 2 for
// bad input (options, project, output folder, a merge with tiles missing), 1 when baking fails.
#include <unistd.h>

#include <cstdio>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "command_registry.h"
#include "terrasynth_flags/flag_checks.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain.h"
#include "terrasynth/tileset_bake.h"

namespace terrasynth::cli {
namespace {

const char* kCommand = "bake";
constexpr int kBadInput = 2;

struct BakeArgs {
    std::string project, output, merge, shard, tileset = "auto", heightmaps = "none", progress = "auto";
    std::vector<int64_t> region;
    int tile = 256, levels = 4, threads = 0;
    bool quantize = false, masks = false, prepare = false;
};

// Exit code and message of a failed step.
struct Failure {
    int code = 0;
    std::string message;
};

Failure badInput(const std::string& message) { return {kBadInput, message}; }

bool parseShard(const std::string& text, int* index, int* count) {
    static const std::regex pattern(R"(^\s*(\d{1,9})\s*/\s*(\d{1,9})\s*$)");
    std::smatch m;
    if (!std::regex_match(text, m, pattern)) return false;
    *index = std::stoi(m[1].str());
    *count = std::stoi(m[2].str());
    return true;
}

// FNV-1a of the project file: bakes of different projects never share a folder.
std::string projectId(const std::string& path) {
    auto bytes = readFileBytes(path);
    uint64_t h = 1469598103934665603ull;
    if (bytes)
        for (unsigned char c : *bytes) h = (h ^ c) * 1099511628211ull;
    char text[32];
    std::snprintf(text, sizeof text, "project-%016llx", static_cast<unsigned long long>(h));
    return text;
}

// Tiles done / total and tiles per second on stderr: one redrawn bar on a terminal, else a line every
// 10% (and at the end).
class ProgressPrinter {
public:
    ProgressPrinter(std::string label, std::string mode) : label_(std::move(label)) {
        if (mode == "auto") mode = ::isatty(2) ? "bar" : "lines";
        bar_ = mode == "bar";
        quiet_ = mode == "none";
    }
    void operator()(const BakeProgress& p) {
        if (quiet_ || p.tiles_total == 0) return;
        const double rate = p.seconds > 0 ? (p.tiles_done - p.tiles_skipped) / p.seconds : 0.0;
        const int percent = static_cast<int>(100 * p.tiles_done / p.tiles_total);
        char skipped[48] = "";
        if (p.tiles_skipped) std::snprintf(skipped, sizeof skipped, ", %lld already done", (long long)p.tiles_skipped);
        if (bar_) {
            const int width = 30, filled = static_cast<int>(width * p.tiles_done / p.tiles_total);
            std::fprintf(stderr, "\r%s [%s%s] %lld/%lld tiles %5.1f tiles/s%s ", label_.c_str(), std::string(filled, '#').c_str(),
                         std::string(width - filled, '.').c_str(), (long long)p.tiles_done, (long long)p.tiles_total, rate, skipped);
            if (p.tiles_done == p.tiles_total) std::fputc('\n', stderr);
        } else if (p.tiles_done == p.tiles_total || percent / 10 > last_decile_) {
            last_decile_ = percent / 10;
            std::fprintf(stderr, "%s: %lld/%lld tiles (%d%%), %.1f tiles/s%s\n", label_.c_str(), (long long)p.tiles_done,
                         (long long)p.tiles_total, percent, rate, skipped);
        }
        std::fflush(stderr);
    }

private:
    std::string label_;
    bool bar_ = false, quiet_ = false;
    int last_decile_ = 0;
};

Failure runMerge(const std::string& folder) {
    if (auto plan = findMissingTiles(folder); !plan) return badInput(plan.message());  // not a bake folder
    std::vector<std::string> refused;
    auto merged = mergeTileset(folder, &refused);  // refuses, naming them, when tiles are missing or damaged
    if (!merged) return {refused.empty() ? 1 : kBadInput, merged.message()};
    std::printf("wrote %s/tileset.json: %lld tiles, %d levels, %s tiling, root geometric error %.1f m, %.1f MB of tiles\n",
                folder.c_str(), (long long)merged->tiles, merged->depth, merged->implicit ? "implicit" : "explicit",
                merged->root_geometric_error_m, merged->content_bytes / 1e6);
    return {};
}

// The options that need no project: checked first, so bad ones never open the project or create files.
Failure parseOptions(const BakeArgs& a, BakeOptions* o) {
    if (!a.shard.empty() && !parseShard(a.shard, &o->shard_index, &o->shard_count))
        return badInput("--shard " + a.shard + ": expected I/N, e.g. 0/4");
    if (!a.region.empty()) {
        if (a.region.size() != 4) return badInput("--region: expected X,Y,W,H");
        if (a.region[2] < 2 || a.region[3] < 2 || a.region[2] > (int64_t(1) << 30) || a.region[3] > (int64_t(1) << 30))
            return badInput("--region " + std::to_string(a.region[2]) + "x" + std::to_string(a.region[3]) +
                            ": W and H must be 2..2^30 samples");
        o->region = {a.region[0], a.region[1], static_cast<int>(a.region[2]), static_cast<int>(a.region[3])};
    }
    o->tile_size = a.tile;
    o->levels = a.levels;
    o->quantize = a.quantize;
    o->threads = a.threads;
    if (a.tileset == "explicit") o->layout = TilesetLayout::Explicit;
    else if (a.tileset == "implicit") o->layout = TilesetLayout::Implicit;
    else if (a.tileset != "auto") return badInput("--tileset: expected auto, explicit or implicit, got " + a.tileset);
    if (a.heightmaps == "png") o->heightmaps = HeightmapFormat::Png16;
    else if (a.heightmaps == "f32") o->heightmaps = HeightmapFormat::Float32;
    else if (a.heightmaps == "tif") o->heightmaps = HeightmapFormat::GeoTiff;
    else if (a.heightmaps != "none") return badInput("--heightmaps: expected png, f32 or tif, got " + a.heightmaps);
    o->type_masks = a.masks;
    // Everything but the terrain's own numbers, so shard and size errors come before the project opens.
    BakeOptions early = *o;
    early.max_source_level = 64;
    early.type_names = {"any"};
    if (early.region.empty()) early.region = {0, 0, 2, 2};
    if (Status s = checkBakeOptions(early); !s) return badInput(s.message());
    return {};
}

Failure runBake(const BakeArgs& a) {
    if (!a.merge.empty()) {
        if (!a.project.empty() || !a.output.empty()) return badInput("--merge takes only the output folder");
        return runMerge(a.merge);
    }
    if (a.project.empty()) return badInput("give a project file (or --merge FOLDER)");
    if (a.output.empty()) return badInput("give the output folder with -o");
    BakeOptions options;
    if (Failure f = parseOptions(a, &options); f.code) return f;

    auto terrain = Terrain::open(a.project);
    if (!terrain) return badInput(terrain.message());
    std::shared_ptr<Terrain> t = *terrain;
    if (options.region.empty()) options.region = t->extent();
    options.meters_per_pixel = t->metersPerPixel(0);
    options.max_source_level = t->database().levelCount() - 1;
    options.type_names = t->database().type_names;
    options.source_id = projectId(a.project);
    if (Status s = checkBakeOptions(options); !s) return badInput(s.message());
    if (Status s = prepareBakeFolder(a.output, options); !s) return badInput(s.message());
    if (a.prepare) {  // the database is built (or found) and the plan written: what every shard reads
        const BakeCounts counts = countBakeTiles(options);
        std::printf("prepared %s: %lld tiles in %lld units, %d levels of tree\n", a.output.c_str(), (long long)counts.tiles,
                    (long long)counts.units, counts.depth);
        return {};
    }

    const bool sharded = !a.shard.empty();
    const std::string label =
        sharded ? "bake shard " + std::to_string(options.shard_index) + "/" + std::to_string(options.shard_count) : "bake";
    auto printer = std::make_shared<ProgressPrinter>(label, a.progress);
    options.progress = [printer](const BakeProgress& p) { (*printer)(p); };
    const BakeSource source = [t, &options](const PixelWindow& w, int level, bool want_types) -> Result<BakeSamples> {
        auto out = t->synthesize(w, level, want_types);
        if (!out) return out.status();
        BakeSamples samples;
        samples.heights = std::move(out->heights);
        if (want_types) samples.types = typesFromSources(out->source_exemplar, t->database().exemplar_type);
        return samples;
    };
    auto stats = bakeTiles(a.output, source, options);
    if (!stats) return {1, stats.message()};
    std::printf("%s: %lld tiles baked, %lld already complete, %.1f MB in %.2f s\n", label.c_str(),
                (long long)stats->tiles_baked, (long long)stats->tiles_skipped, stats->bytes_written / 1e6, stats->seconds);
    return sharded ? Failure{} : runMerge(a.output);
}

void addBakeCommand(CLI::App& app) {
    auto a = std::make_shared<BakeArgs>();
    CLI::App* cmd = app.add_subcommand("bake", "Bake a region into a 3D Tiles 1.1 tileset of glTF tiles, whole or by shard");
    cmd->add_option("project", a->project, "Project file (.tsyn)");
    cmd->add_option("-o,--output", a->output, "Output folder (created; shards of one bake share it)");
    cmd->add_option("--merge", a->merge, "Write FOLDER/tileset.json from the tiles the shards baked");
    cmd->add_option("--region", a->region, "X,Y,W,H level-0 samples (default: the project extent)")
        ->delimiter(',')
        ->check(flags::FiniteRange(ranges::kRegionNumber));
    cmd->add_option("--tile", a->tile, "Quads per tile side (2..4096)")->check(flags::FiniteRange(2, 4096));
    cmd->add_option("--levels", a->levels, "Levels of detail: quadtree levels with content (1..16)")->check(flags::FiniteRange(1, 16));
    cmd->add_flag("--quantize", a->quantize, "KHR_mesh_quantization: 16-bit positions, 8-bit normals, 16-bit indices");
    cmd->add_option("--tileset", a->tileset, "auto (implicit for deep trees), explicit or implicit");
    cmd->add_option("--heightmaps", a->heightmaps, "Per-leaf heightmaps: png (16-bit + sidecar), f32 or tif");
    cmd->add_flag("--masks", a->masks, "Per-leaf splat masks, one 8-bit PNG per terrain type");
    cmd->add_option("--shard", a->shard, "Bake only shard I of N (I/N); run --merge when all are done");
    cmd->add_flag("--prepare", a->prepare, "Only build the project's database and write the plan (before a sharded bake)");
    cmd->add_option("--threads", a->threads, "Worker threads (default: all cores)")->check(flags::FiniteRange(ranges::kThreads));
    cmd->add_option("--progress", a->progress, "auto (bar on a terminal, else lines), bar, lines or none");
    cmd->callback([a] {
        const Failure f = runBake(*a);
        if (f.code) {
            fail(kCommand, f.message);
            exitCode() = f.code;
        }
    });
}

const CommandRegistration kReg{"bake", 65, addBakeCommand, kBadInput};

}  // namespace
}  // namespace terrasynth::cli
