// `terrasynth export <project.tsyn> | --heightmap in.png  -o out.glb|.gltf|.png|.f32|.exr|.tif
//   [--region X,Y,W,H] [--level L] [--tile 256] [--lods N] [--lod-method grid|simplify]
//   [--lod-layout files|msft] [--quantize]
//   [--colors] [--texture N] [--masks PREFIX [--mask-blur R]]`
// `terrasynth export <project.tsyn> | --heightmap in.png --preset unreal|unity|godot -o out.png|.r16|.raw|.exr`
// Meshes (glTF 2.0) or heightmaps of a project's terrain or of any exemplar file; docs/export.md.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command_registry.h"
#include "terrasynth_flags/flag_checks.h"
#include "outputs.h"
#include "terrasynth/engine_heightmap.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/limits.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain.h"

namespace terrasynth::cli {
namespace {

const char* kCommand = "export";

struct ExportArgs {
    std::string project, heightmap, output, masks, preset;
    std::vector<int64_t> region;
    int level = 0, tile = 256, lods = 1, texture = 0, mask_blur = 0;
    std::string lod_method = "grid", lod_layout = "files";
    bool quantize = false, colors = false;
};

// Where heights (and types) come from: a project's Terrain or a heightfield file.
struct Input {
    HeightSource heights;
    TypeSource types;
    std::vector<std::string> type_names;
    std::function<Result<std::vector<uint8_t>>(const PixelWindow&, int)> types_for_masks;
    PixelWindow extent;
};

Result<Input> openInput(const ExportArgs& a) {
    Input in;
    if (!a.heightmap.empty()) {
        auto exemplar = readExemplar(a.heightmap);
        if (!exemplar) return exemplar.status();
        in.extent = {0, 0, exemplar->field.width, exemplar->field.height};
        in.heights = heightSourceFromField(std::move(exemplar->field));
        return in;
    }
    TerrainOptions options;
    options.on_warning = warn;
    auto terrain = Terrain::open(a.project, options);
    if (!terrain) return terrain.status();
    std::shared_ptr<Terrain> t = *terrain;
    in.extent = t->extent();
    in.heights = [t](const PixelWindow& w, int level) { return t->heights(w, level); };
    in.types = [t](const PixelWindow& w, int level) -> Result<std::vector<uint8_t>> {
        auto out = t->synthesize(w, level, /*want_sources=*/true);
        if (!out) return out.status();
        return typesFromSources(out->source_exemplar, t->database().exemplar_type);
    };
    in.type_names = t->database().type_names;
    return in;
}

// Every file the export will write, checked before any work. Mask names depend on the database's
// type names, so the masks' folder is checked here and their names when they are staged.
Status checkExportOutputs(const ExportArgs& a) {
    std::vector<PlannedOutput> planned = {{"-o", a.output}};
    if (isGltfPath(a.output)) {
        const int files = a.lod_layout == "files" ? a.lods : 1;
        for (int lod = 0; lod < files; ++lod) {
            const std::string file = gltfLodPath(a.output, lod);
            if (lod > 0) planned.push_back({"-o (LOD " + std::to_string(lod) + ")", file});
            if (hasSuffix(file, ".gltf")) planned.push_back({"-o (its .bin)", file.substr(0, file.size() - 5) + ".bin"});
        }
    } else {
        if (Status s = checkHeightmapExportPath(a.output); !s) return s.withContext("-o");
        if (!hasSuffix(a.output, ".exr") && !hasSuffix(a.output, ".tif") && !hasSuffix(a.output, ".tiff"))
            planned.push_back({"-o (its sidecar)", sidecarOf(a.output)});
    }
    if (!a.masks.empty()) planned.push_back({"--masks", a.masks + "mask.png"});
    return checkOutputs(planned);
}

// --preset: the region fitted to the engine's sizes, heightmap tiles, splat masks (projects) and the
// JSON with the import numbers, all in one transaction.
Status runPreset(const ExportArgs& a, const Input& input, const PixelWindow& region) {
    auto engine = engineNamed(a.preset);
    if (!engine) return engine.status().withContext("--preset");
    auto plan = planEngineHeightmap(*engine, region, /*endless=*/a.heightmap.empty());
    if (!plan) return plan.status().withContext("--preset " + a.preset);
    EngineExportOptions options;
    options.path = a.output;
    options.level = a.level;
    options.types = input.types;
    options.type_names = input.type_names;
    options.mask_blur = a.mask_blur;
    FileTransaction transaction;
    auto written = stageEngineHeightmap(transaction, *plan, input.heights, options);
    if (!written) return written.status();
    if (Status s = transaction.commit(); !s) return s;
    for (const std::string& f : written->files) std::printf("wrote %s\n", f.c_str());
    std::printf("%s\n", written->summary.c_str());
    return Status::ok();
}

Status runExport(const ExportArgs& a) {
    if (a.project.empty() == a.heightmap.empty()) return Status::error("give either a project or --heightmap");
    if (!a.preset.empty() && (isGltfPath(a.output) || !a.masks.empty()))
        return Status::error("--preset writes engine heightmaps (and their masks): -o must be .png, .r16, .raw or .exr, "
                             "without --masks");
    if (Status s = a.preset.empty() ? checkExportOutputs(a) : checkOutputs({{"-o", a.output}}); !s) return s;
    auto input = openInput(a);
    if (!input) return input.status();
    PixelWindow region = input->extent;
    if (!a.region.empty()) {
        if (a.region.size() != 4) return Status::error("--region: expected X,Y,W,H");
        if (a.region[2] < 2 || a.region[3] < 2 || a.region[2] > limits::kMaxWindowSide || a.region[3] > limits::kMaxWindowSide)
            return Status::error("--region: W and H must be 2.." + std::to_string(limits::kMaxWindowSide));
        if (a.region[0] < -limits::kMaxWindowOrigin || a.region[0] > limits::kMaxWindowOrigin ||
            a.region[1] < -limits::kMaxWindowOrigin || a.region[1] > limits::kMaxWindowOrigin)
            return Status::error("--region: X and Y must be within +-2^29");
        region = {a.region[0], a.region[1], static_cast<int>(a.region[2]), static_cast<int>(a.region[3])};
    }
    if (a.level > 0 && a.region.empty()) {  // the extent shrinks with the level
        region.x >>= a.level, region.y >>= a.level;
        region.width = std::max(2, region.width >> a.level), region.height = std::max(2, region.height >> a.level);
    }

    if (!a.preset.empty()) return runPreset(a, *input, region);

    // Masks and the export change together: one transaction, committed at the end.
    FileTransaction transaction;
    std::vector<std::string> mask_paths;
    if (!a.masks.empty()) {
        if (!input->types) return Status::error("--masks needs a project (a coordinate map), not --heightmap");
        auto types = input->types(region, a.level);
        if (!types) return types.status();
        TypeMaskOptions mask_options;
        mask_options.blur_radius = a.mask_blur;
        auto paths = stageTypeMasks(transaction, a.masks, region.width, region.height, *types, input->type_names, mask_options);
        if (!paths) return paths.status();
        mask_paths = std::move(*paths);
    }

    if (!isGltfPath(a.output)) {
        auto field = input->heights(region, a.level);
        if (!field) return field.status();
        if (Status s = stageHeightmapExport(transaction, a.output, *field, region); !s) return s;
        if (Status s = transaction.commit(); !s) return s;
        for (const std::string& p : mask_paths) std::printf("wrote %s\n", p.c_str());
        std::printf("wrote %s (%dx%d heights)\n", a.output.c_str(), field->width, field->height);
        return Status::ok();
    }

    GltfExportOptions options;
    options.region = region;
    options.level = a.level;
    options.tile_size = a.tile;
    options.lods = a.lods;
    if (a.lod_method == "simplify") options.lod_method = LodMethod::Simplify;
    else if (a.lod_method != "grid") return Status::error("--lod-method: expected grid or simplify, got " + a.lod_method);
    if (a.lod_layout == "msft") options.lod_layout = LodLayout::MsftLod;
    else if (a.lod_layout != "files") return Status::error("--lod-layout: expected files or msft, got " + a.lod_layout);
    options.quantize = a.quantize;
    options.vertex_colors = a.colors;
    options.texture_size = a.texture;
    if (a.colors || a.texture > 0) options.types = input->types;
    auto stats = stageGltf(transaction, a.output, input->heights, options);
    if (!stats) return stats.status();
    if (Status s = transaction.commit(); !s) return s;
    for (const std::string& p : mask_paths) std::printf("wrote %s\n", p.c_str());
    std::printf("wrote %s: %d x %d tiles, %d LODs, %zu bytes (JSON %zu, binary %zu)\n", a.output.c_str(), stats->tiles_x,
                stats->tiles_y, a.lods, stats->file_bytes, stats->json_bytes, stats->binary_bytes);
    for (size_t k = 1; k < stats->files.size(); ++k) std::printf("wrote %s: LOD %zu\n", stats->files[k].c_str(), k);
    for (size_t k = 0; k < stats->lods.size(); ++k)
        std::printf("  LOD %zu: %zu vertices, %zu triangles, geometric error up to %.2f m\n", k, stats->lods[k].vertices,
                    stats->lods[k].triangles, stats->lods[k].max_geometric_error_m);
    return Status::ok();
}

void addExportCommand(CLI::App& app) {
    auto a = std::make_shared<ExportArgs>();
    CLI::App* cmd = app.add_subcommand("export", "Export terrain as glTF 2.0 (tiles + LODs), a heightmap or type masks");
    cmd->add_option("project", a->project, "Project file (.tsyn)");
    cmd->add_option("--heightmap", a->heightmap, "Export this heightfield file (any exemplar format) instead of a project");
    cmd->add_option("-o,--output", a->output,
                    "Output: .glb/.gltf mesh, or .png (16-bit + sidecar) / .f32 / .exr / .tif heightmap")
        ->required();
    cmd->add_option("--region", a->region, "X,Y,W,H samples of the global grid (default: the project extent)")
        ->delimiter(',')
        ->check(flags::FiniteRange(ranges::kRegionNumber));
    cmd->add_option("--level", a->level, "Pyramid level (0 = full resolution)")->check(flags::FiniteRange(ranges::kOutputLevel));
    cmd->add_option("--tile", a->tile, "Quads per tile side")->check(flags::FiniteRange(ranges::kGltfTileQuads));
    cmd->add_option("--lods", a->lods, "Levels of detail per tile (see --lod-layout)")->check(flags::FiniteRange(ranges::kGltfLods));
    cmd->add_option("--lod-method", a->lod_method, "grid (stitched, fast) or simplify (meshoptimizer)");
    cmd->add_option("--lod-layout", a->lod_layout,
                    "files (default: one whole terrain per LOD, out.glb, out_lod1.glb, ...) or msft (one file, MSFT_lod)");
    cmd->add_flag("--quantize", a->quantize, "KHR_mesh_quantization: 16-bit positions, 8-bit normals, 16-bit indices");
    cmd->add_flag("--colors", a->colors, "Vertex colours: hypsometric tint (+ terrain types for projects)");
    cmd->add_option("--texture", a->texture, "Embed a tint texture of at most N pixels per side")->check(flags::FiniteRange(ranges::kTextureSize));
    cmd->add_option("--masks", a->masks, "Also write one PNG mask per terrain type: PREFIX<type>.png (projects only)");
    cmd->add_option("--mask-blur", a->mask_blur, "Blur radius (pixels) for soft splat masks")->check(flags::FiniteRange(ranges::kMaskBlur));
    cmd->add_option("--preset", a->preset,
                    "unreal|unity|godot: a heightmap in the engine's sizes and format (tiled when larger than one "
                    "landscape), splat masks beside it, and <stem>.json + a printed line with the import numbers");
    setAction(cmd, [a] {
        if (Status s = runExport(*a); !s) fail(kCommand, s.message());
    });
}

const CommandRegistration kReg{"export", 60, addExportCommand};

}  // namespace
}  // namespace terrasynth::cli
