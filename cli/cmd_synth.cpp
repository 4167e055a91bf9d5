// terrasynth synth <project.tsyn | --db db.tsdb> -o out.png|out.f32|out.exr|out.tif [--size WxH] [--origin X,Y]
//                  [--seed N] [--level L] [--sources src.png] [--preview hillshade.png] [--backend opencl|reference]
//                  [--drainage off|breach] [--relax-offsets on|off]
//                  [--coherent-with previous.tsyn]
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "terrasynth_flags/flag_checks.h"
#include "outputs.h"
#include "terrasynth/curve_course.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain.h"

namespace terrasynth::cli {
namespace {

struct SynthArgs {
    std::string project, database, output, sources, preview, size, origin, coherent_with, backend = "opencl", drainage;
    std::string relax_offsets;
    int64_t seed = -1;
    int level = 0;
};

bool parsePair(const std::string& text, char separator, int64_t* a, int64_t* b) {
    const size_t at = text.find(separator);
    if (at == std::string::npos) return false;
    try {
        size_t used = 0;
        *a = std::stoll(text.substr(0, at), &used);
        if (used != at) return false;
        *b = std::stoll(text.substr(at + 1), &used);
        return used == text.size() - at - 1;
    } catch (...) {
        return false;
    }
}

// Sources map (issue: "R,G = exemplar x,y; B = exemplar id") as a 16-bit RGB PNG, with a sidecar
// naming the exemplars so materials can be transferred from them. Staged: the PNG, then its sidecar.
Status stageSourcesMap(FileTransaction& transaction, const std::string& path, const SynthesisOutput& out,
                       const ExemplarDatabase& db, int level) {
    const Heightfield& h = out.heights;
    std::vector<uint16_t> rgb(h.size() * 3);
    for (size_t i = 0; i < h.size(); ++i) {
        rgb[3 * i] = static_cast<uint16_t>(std::lround(std::clamp(out.source_x[i], 0.0f, 65535.0f)));
        rgb[3 * i + 1] = static_cast<uint16_t>(std::lround(std::clamp(out.source_y[i], 0.0f, 65535.0f)));
        rgb[3 * i + 2] = out.source_exemplar[i];
    }
    nlohmann::json side = {{"file", path.substr(path.find_last_of('/') + 1)},
                           {"channels", "R = exemplar x, G = exemplar y (pixels of the exemplar resampled to the "
                                        "database spacing, at this level), B = exemplar index"},
                           {"level", level},
                           {"exemplar_meters_per_pixel", db.meters_per_pixel * std::ldexp(1.0, level)}};
    for (size_t e = 0; e < db.exemplars.size(); ++e)
        side["exemplars"].push_back({{"index", e}, {"name", db.exemplars[e].name}, {"path", db.exemplars[e].path},
                                     {"type", db.type_names[db.exemplar_type[e]]}});
    if (Status s = stagePng16(transaction, path, h.width, h.height, 3, rgb); !s) return s;
    return transaction.stage(sidecarOf(path), jsonText(side, 1) + "\n");
}

// How close each point constraint's site and each curve's course in the window came to their
// heights (s5.1), so a user can check a project from the command line.
void reportHeldConstraints(const Terrain& terrain, const PixelWindow& window, const Heightfield& heights) {
    const auto& constraints = terrain.project().synthesis.constraints;
    if (!constraints) return;
    const HeightRange range = heightRange(heights);
    const double relief = std::max(1e-3f, range.max - range.min);
    for (size_t i = 0; i < constraints->curves.size(); ++i) {
        const CurveHold hold = measureCurveHold(heights, window.x, window.y, constraints->curves, i, heights.meters_per_pixel_x);
        std::vector<float> miss = hold.height_error_m;
        if (miss.empty()) continue;
        for (float& m : miss) m = std::fabs(m);
        std::sort(miss.begin(), miss.end());
        const float median = miss[miss.size() / 2], p95 = miss[std::min(miss.size() - 1, miss.size() * 95 / 100)];
        std::printf("curve %zu: course %.1f m from its widgets' heights at the median (%.2f%% of the relief), %.1f m at the "
                    "95th percentile (%.2f%%)\n",
                    i, median, 100.0 * median / relief, p95, 100.0 * p95 / relief);
    }
    for (size_t i = 0; i < constraints->points.size(); ++i) {
        const PointConstraint& p = constraints->points[i];
        const int64_t x = std::llround(p.x), y = std::llround(p.y);
        if (x < window.x || y < window.y || x >= window.x + window.width || y >= window.y + window.height) continue;
        const float h = heights.at(static_cast<int>(x - window.x), static_cast<int>(y - window.y));
        std::printf("point %zu at (%lld, %lld): asked %.1f m, synthesized %.1f m (%.2f%% of the relief)\n", i,
                    static_cast<long long>(x - terrain.project().origin_x), static_cast<long long>(y - terrain.project().origin_y),
                    p.height_m, h, 100.0 * std::fabs(h - p.height_m) / std::max(1e-3f, range.max - range.min));
    }
}

// The project (or a bare database) with the command line's overrides applied.
Result<Project> projectWithOverrides(const std::string& project_path, const SynthArgs& args) {
    Project project;
    if (!project_path.empty()) {
        auto loaded = loadProject(project_path);
        if (!loaded) return loaded.status();
        project = std::move(loaded.value());
    } else if (!args.database.empty()) {
        project.database = args.database;
    } else {
        return Status::error("give a project file or --db database.tsdb");
    }
    if (!args.size.empty()) {
        int64_t w = 0, h = 0;
        if (!parsePair(args.size, 'x', &w, &h) || w < 1 || h < 1 || w > 16384 || h > 16384)
            return Status::error("--size must be WxH with sides 1..16384, got \"" + args.size + "\"");
        project.width = static_cast<int>(w), project.height = static_cast<int>(h);
    }
    if (!args.origin.empty() && !parsePair(args.origin, ',', &project.origin_x, &project.origin_y))
        return Status::error("--origin must be X,Y, got \"" + args.origin + "\"");
    if (args.seed >= 0) project.synthesis.seed = static_cast<uint32_t>(args.seed);
    if (args.drainage == "off") project.synthesis.drainage = Drainage::Off;
    else if (args.drainage == "breach") project.synthesis.drainage = Drainage::Breach;
    else if (!args.drainage.empty()) return Status::error("--drainage must be off or breach, got \"" + args.drainage + "\"");
    if (args.relax_offsets == "on" || args.relax_offsets == "off") project.synthesis.relax_offsets = args.relax_offsets == "on";
    else if (!args.relax_offsets.empty())
        return Status::error("--relax-offsets must be on or off, got \"" + args.relax_offsets + "\"");
    return project;
}

// Everything `synth` will write, checked before any synthesis.
Status checkSynthOutputs(const SynthArgs& args) {
    if (Status s = checkHeightmapExportPath(args.output); !s) return s;
    std::vector<PlannedOutput> planned = {{"-o", args.output}};
    if (!hasSuffix(args.output, ".exr") && !hasSuffix(args.output, ".tif") && !hasSuffix(args.output, ".tiff"))
        planned.push_back({"-o (its sidecar)", sidecarOf(args.output)});
    if (!args.preview.empty()) {
        if (!hasSuffix(args.preview, ".png")) return Status::error("--preview: " + args.preview + ": must end in .png");
        planned.push_back({"--preview", args.preview});
    }
    if (!args.sources.empty()) {
        if (!hasSuffix(args.sources, ".png")) return Status::error("--sources: " + args.sources + ": must end in .png");
        planned.push_back({"--sources", args.sources});
        planned.push_back({"--sources (its sidecar)", sidecarOf(args.sources)});
    }
    return checkOutputs(planned);
}

// All outputs in one transaction: the preview and sources map first, the heightmap and its sidecar
// last; on any failure every previous file stays as it was. `window` places a GeoTIFF in the local
// metric frame (grid.h: x east, y north, metres; the global pixel grid's origin at 0, 0).
Status writeOutputs(const SynthArgs& args, const Heightfield& heights, const PixelWindow& window,
                    const SynthesisOutput* sources = nullptr, const ExemplarDatabase* db = nullptr) {
    FileTransaction transaction;
    if (!args.preview.empty())
        if (Status s = stageHillshadePng(transaction, args.preview, heights); !s) return s;
    if (sources)
        if (Status s = stageSourcesMap(transaction, args.sources, *sources, *db, args.level); !s) return s;
    if (Status s = stageHeightmapExport(transaction, args.output, heights, window); !s) return s;
    return transaction.commit();
}

// --coherent-with: the project as an edit of another (s5.3), re-synthesizing only what changed.
void runCoherentEdit(const SynthArgs& args, const TerrainOptions& options, Terrain& edited) {
    if (!args.sources.empty() || args.level != 0)
        return fail("synth", "--coherent-with writes level-0 heights only (no --sources, no --level)");
    auto previous_project = projectWithOverrides(args.coherent_with, args);
    if (!previous_project) return fail("synth", previous_project.message());
    auto previous = Terrain::fromProject(previous_project.value(), options);
    if (!previous) return fail("synth", previous.message());
    const auto start = std::chrono::steady_clock::now();
    PixelWindow changed;
    Heightfield before;
    auto heights = edited.heightsAfterEditOf(*previous.value(), &changed, &before);
    if (!heights) return fail("synth", heights.message());
    const auto done = std::chrono::steady_clock::now();
    Status s = writeOutputs(args, heights.value(), edited.extent());
    if (!s) return fail("synth", s.message());
    // How far the edit reached: the box of what changed, and how much of the extent moved by more than 1 m.
    size_t moved = 0;
    for (size_t i = 0; i < heights->heights.size(); ++i) moved += std::fabs(heights->heights[i] - before.heights[i]) > 1.0f;
    std::printf("wrote %s: %dx%d as an edit of %s in %.1f ms\n", args.output.c_str(), heights->width, heights->height,
                args.coherent_with.c_str(), std::chrono::duration<double, std::milli>(done - start).count());
    std::printf("heights changed within %dx%d pixels at (%lld, %lld); %zu of %zu pixels (%.3f%%) moved > 1 m\n",
                changed.width, changed.height, static_cast<long long>(changed.x - edited.extent().x),
                static_cast<long long>(changed.y - edited.extent().y), moved, heights->heights.size(),
                100.0 * moved / std::max<size_t>(1, heights->heights.size()));
    reportHeldConstraints(edited, edited.extent(), heights.value());
}

void runSynth(const SynthArgs& args) {
    // Refuse unwritable outputs before spending time on synthesis.
    if (Status s = checkSynthOutputs(args); !s) return fail("synth", s.message());
    auto loaded = projectWithOverrides(args.project, args);
    if (!loaded) return fail("synth", loaded.message());
    const Project& project = loaded.value();
    TerrainOptions options;
    options.on_warning = warn;
    if (args.backend == "reference") options.synthesizer.backend = SynthesisBackend::Reference;
    else if (args.backend != "opencl") return fail("synth", "--backend must be opencl or reference");
    const auto start = std::chrono::steady_clock::now();
    auto terrain = Terrain::fromProject(project, options);
    if (!terrain) return fail("synth", terrain.message());
    if (!args.coherent_with.empty()) return runCoherentEdit(args, options, *terrain.value());
    const auto ready = std::chrono::steady_clock::now();
    PixelWindow window = terrain.value()->extent();
    if (args.level > 0) {  // the extent at a coarser level covers the same ground
        window.x >>= args.level, window.y >>= args.level;
        window.width = std::max(1, window.width >> args.level), window.height = std::max(1, window.height >> args.level);
    }
    auto out = terrain.value()->synthesize(window, args.level, !args.sources.empty());
    if (!out) return fail("synth", out.message());
    const auto done = std::chrono::steady_clock::now();
    Status s = writeOutputs(args, out->heights, window, args.sources.empty() ? nullptr : &out.value(),
                            &terrain.value()->database());
    if (!s) return fail("synth", s.message());
    const HeightRange range = heightRange(out->heights);
    std::printf("wrote %s: %dx%d at %.2f m/pixel, heights %.1f..%.1f m, seed %u\n", args.output.c_str(),
                out->heights.width, out->heights.height, out->heights.meters_per_pixel_x, range.min, range.max,
                project.synthesis.seed);
    std::printf("database + device ready in %.2f s, synthesis %.1f ms\n",
                std::chrono::duration<double>(ready - start).count(),
                std::chrono::duration<double, std::milli>(done - ready).count());
    if (args.level == 0) reportHeldConstraints(*terrain.value(), window, out->heights);
}

void addSynthCommand(CLI::App& app) {
    auto args = std::make_shared<SynthArgs>();
    auto* cmd = app.add_subcommand("synth", "Synthesize a terrain (paper s4) and write it as a heightmap");
    cmd->add_option("project", args->project, "Project file (.tsyn)");
    cmd->add_option("--db", args->database, "Database file (.tsdb) instead of a project");
    cmd->add_option("-o,--output", args->output, "Heightmap to write: .png (16-bit + sidecar), .f32, .exr, .tif (float32 GeoTIFF, local metric CRS)")->required();
    cmd->add_option("--size", args->size, "WxH in pixels (default: the project's, 1024x1024)");
    cmd->add_option("--origin", args->origin, "X,Y global pixel of the north-west corner (default 0,0)");
    cmd->add_option("--seed", args->seed, "Random seed (default: the project's)")->check(flags::FiniteRange(ranges::kSeed));
    cmd->add_option("--level", args->level, "Pyramid level to output (0 = full resolution)")->check(flags::FiniteRange(ranges::kOutputLevel));
    cmd->add_option("--sources", args->sources, "Write the exemplar coordinate map (16-bit RGB PNG)");
    cmd->add_option("--preview", args->preview, "Write a hillshade preview PNG");
    cmd->add_option("--backend", args->backend, "opencl (default) or reference (plain C++)");
    cmd->add_option("--drainage", args->drainage,
                    "breach (carve closed pits so the terrain drains) or off (no drainage step); default: the "
                    "project's, breach when it names none");
    cmd->add_option("--relax-offsets", args->relax_offsets,
                    "on (height steps made the exemplars' own across patches) or off (the paper's offsets); default: the project's");
    cmd->add_option("--coherent-with", args->coherent_with,
                    "Previous version of the project (.tsyn): re-synthesize only where the constraints changed (s5.3)");
    setAction(cmd, [args] { runSynth(*args); });
}

const CommandRegistration kRegistration{"synth", 20, addSynthCommand};

}  // namespace
}  // namespace terrasynth::cli
