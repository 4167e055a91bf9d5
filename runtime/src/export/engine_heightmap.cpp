// Engine presets: the region fitted to the engine's sizes, cut into tiles where one landscape is not
// enough, 16-bit heights over the region's range, splat masks, and the import numbers.
#include "terrasynth/engine_heightmap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/json_reader.h"
#include "core/paths.h"
#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth {
namespace {

const char* engineName(Engine e) { return e == Engine::Unreal ? "unreal" : e == Engine::Unity ? "unity" : "godot"; }

// Samples per side of one landscape: the largest that fits (or, growing, the smallest that covers)
// `side`, from `sizes` (ascending). 0 when none fits.
int fitSize(const std::vector<int>& sizes, int side, bool grow) {
    if (grow) {
        for (int s : sizes)
            if (s >= side) return s;
        return 0;
    }
    int best = 0;
    for (int s : sizes)
        if (s <= side) best = s;
    return best;
}

std::vector<int> unrealSizes(int component_quads) {
    std::vector<int> sizes;
    for (int n = 1; n <= 32; n *= 2) sizes.push_back(n * component_quads + 1);
    return sizes;
}

constexpr int kUnrealMaxSide = 8129, kUnrealTileSide = 2017;  // 32 x 254 + 1; 16 x 126 + 1
constexpr int kUnityMaxSide = 4097, kGodotMaxSide = 16384;  // Terrain3D: a 16k^2 world

// Tiles of `tile` samples sharing `shared` edge samples that cover (grow) or fit in `side` samples.
int tileCount(int side, int tile, int shared, bool grow) {
    const int step = tile - shared;
    return grow ? std::max(1, (side - shared + step - 1) / step) : (side - shared) / step;
}

Result<EnginePlan> planUnreal(EnginePlan plan, bool grow) {
    const int w = plan.region.width, h = plan.region.height, side = std::max(w, h);
    // One landscape holds what fits 8129 samples a side; a file is tiled only when even its shorter side is longer.
    const bool tiled = grow ? side > kUnrealMaxSide : std::min(w, h) > kUnrealMaxSide;
    if (tiled) {
        plan.component_quads = 126;
        plan.tile_width = plan.tile_height = kUnrealTileSide;
        plan.tiles_x = tileCount(w, kUnrealTileSide, 1, grow), plan.tiles_y = tileCount(h, kUnrealTileSide, 1, grow);
        plan.tile_step_x = plan.tile_step_y = kUnrealTileSide - 1;
    } else {
        // 63-quad sections up to 4033 samples, 127-quad sections for 8129.
        const int larger = fitSize({127, 253, 505, 1009, 2017, 4033, kUnrealMaxSide}, grow ? side : std::min(side, kUnrealMaxSide), grow);
        plan.component_quads = larger == kUnrealMaxSide ? 254 : 126;
        const std::vector<int> sizes = unrealSizes(plan.component_quads);
        plan.tile_width = fitSize(sizes, w, grow), plan.tile_height = fitSize(sizes, h, grow);
        if (plan.tile_width == 0 || plan.tile_height == 0)
            return Status::error("region " + std::to_string(w) + "x" + std::to_string(h) + ": smaller than Unreal's smallest landscape (" +
                                 std::to_string(sizes.front()) + " samples a side)");
    }
    return plan;
}

Result<EnginePlan> planUnity(EnginePlan plan, bool grow) {
    const int w = plan.region.width, h = plan.region.height;
    std::vector<int> sizes;
    for (int s = 33; s <= kUnityMaxSide; s = 2 * s - 1) sizes.push_back(s);
    const bool tiled = grow ? std::max(w, h) > kUnityMaxSide : std::min(w, h) > kUnityMaxSide;
    if (tiled) {
        plan.tile_width = plan.tile_height = kUnityMaxSide;
        plan.tiles_x = tileCount(w, kUnityMaxSide, 1, grow), plan.tiles_y = tileCount(h, kUnityMaxSide, 1, grow);
        plan.tile_step_x = plan.tile_step_y = kUnityMaxSide - 1;
    } else {
        // Unity's heightmaps are square: the larger side grows, or the smaller one bounds the crop.
        plan.tile_width = plan.tile_height = fitSize(sizes, grow ? std::max(w, h) : std::min(w, h), grow);
        if (plan.tile_width == 0)
            return Status::error("region " + std::to_string(w) + "x" + std::to_string(h) + ": smaller than Unity's smallest heightmap (33 samples a side)");
    }
    return plan;
}

// Terrain3D slices and pads any size into its regions itself: the region stays as it is.
Result<EnginePlan> planGodot(EnginePlan plan) {
    if (plan.region.width > kGodotMaxSide || plan.region.height > kGodotMaxSide)
        return Status::error("region " + std::to_string(plan.region.width) + "x" + std::to_string(plan.region.height) +
                             ": larger than a Terrain3D world (" + std::to_string(kGodotMaxSide) + " samples a side)");
    plan.tile_width = plan.region.width, plan.tile_height = plan.region.height;
    return plan;
}

// "_x<i>_y<j>" (Unreal), "_<i>_<z>" (Unity, z from the south); "" untiled.
std::string tileSuffix(const EnginePlan& plan, int tx, int ty) {
    if (plan.tiles_x * plan.tiles_y == 1) return "";
    if (plan.engine == Engine::Unreal) return "_x" + std::to_string(tx) + "_y" + std::to_string(ty);
    return "_" + std::to_string(tx) + "_" + std::to_string(plan.tiles_y - 1 - ty);
}

Status checkExtension(Engine engine, const std::string& path) {
    const std::string ext = detail::lowerExtension(path);
    const bool ok = engine == Engine::Unreal  ? ext == ".png" || ext == ".r16"
                    : engine == Engine::Unity ? ext == ".raw"
                                              : ext == ".r16" || (ext == ".exr" && openExrAvailable());
    if (ok) return Status::ok();
    const char* wanted = engine == Engine::Unreal  ? ".png (16-bit) or .r16"
                         : engine == Engine::Unity ? ".raw (16-bit, Windows byte order)"
                                                   : (openExrAvailable() ? ".r16 or .exr" : ".r16 (.exr needs a build with OpenEXR)");
    return Status::error(path + ": the " + std::string(engineName(engine)) + " preset writes " + wanted);
}

std::string littleEndian16(const std::vector<uint16_t>& samples) {
    std::string bytes(samples.size() * 2, '\0');
    for (size_t i = 0; i < samples.size(); ++i) {
        bytes[2 * i] = static_cast<char>(samples[i] & 0xff);
        bytes[2 * i + 1] = static_cast<char>(samples[i] >> 8);
    }
    return bytes;
}

std::string format(const char* pattern, double a = 0, double b = 0, double c = 0, double d = 0) {
    char text[256];
    std::snprintf(text, sizeof text, pattern, a, b, c, d);
    return text;
}

}  // namespace

PixelWindow EnginePlan::tile(int tx, int ty) const {
    return {region.x + int64_t(tx) * tile_step_x, region.y + int64_t(ty) * tile_step_y, tile_width, tile_height};
}

Result<Engine> engineNamed(const std::string& name) {
    if (name == "unreal") return Engine::Unreal;
    if (name == "unity") return Engine::Unity;
    if (name == "godot") return Engine::Godot;
    return Status::error("unknown engine preset \"" + name + "\" (use unreal, unity or godot)");
}

Result<EnginePlan> planEngineHeightmap(Engine engine, const PixelWindow& region, bool endless) {
    if (region.width < 2 || region.height < 2) return Status::error("the region needs at least 2x2 samples");
    EnginePlan plan;
    plan.engine = engine;
    plan.region = region;
    Result<EnginePlan> fitted = engine == Engine::Unreal  ? planUnreal(plan, endless)
                                : engine == Engine::Unity ? planUnity(plan, endless)
                                                          : planGodot(plan);
    if (!fitted) return fitted;
    EnginePlan& p = fitted.value();
    if (p.tile_step_x == 0) p.tile_step_x = p.tile_width, p.tile_step_y = p.tile_height;
    p.region.width = (p.tiles_x - 1) * p.tile_step_x + p.tile_width;
    p.region.height = (p.tiles_y - 1) * p.tile_step_y + p.tile_height;
    if (uint64_t(p.region.width) * uint64_t(p.region.height) > limits::kMaxImagePixels)
        return Status::error("the " + std::string(engineName(engine)) + " preset makes " + std::to_string(p.region.width) + "x" +
                             std::to_string(p.region.height) + " samples, more than " + std::to_string(limits::kMaxImagePixels) +
                             ": export a smaller region or a coarser --level");
    return fitted;
}

Result<EngineImport> stageEngineHeightmap(FileTransaction& transaction, const EnginePlan& plan, const HeightSource& heights,
                                          const EngineExportOptions& options) {
    if (Status s = checkExtension(plan.engine, options.path); !s) return s;
    if (!heights) return Status::error(options.path + ": no height source");
    const std::string ext = detail::lowerExtension(options.path);
    const std::string stem = options.path.substr(0, options.path.size() - ext.size());

    // Every tile first: the 16-bit range is the whole export's, so tiles meet without a step.
    std::vector<Heightfield> tiles;
    float lo = INFINITY, hi = -INFINITY;
    for (int ty = 0; ty < plan.tiles_y; ++ty)
        for (int tx = 0; tx < plan.tiles_x; ++tx) {
            const PixelWindow w = plan.tile(tx, ty);
            auto field = heights(w, options.level);
            if (!field) return field.status().withContext(options.path + " tile " + std::to_string(tx) + "," + std::to_string(ty));
            if (field->width != w.width || field->height != w.height)
                return Status::error(options.path + ": the source returned " + std::to_string(field->width) + "x" +
                                     std::to_string(field->height) + " samples for a " + std::to_string(w.width) + "x" +
                                     std::to_string(w.height) + " tile");
            const HeightRange r = heightRange(*field);
            lo = std::min(lo, r.min), hi = std::max(hi, r.max);
            tiles.push_back(std::move(*field));
        }
    EngineImport out;
    out.spacing_x_m = tiles[0].meters_per_pixel_x, out.spacing_y_m = tiles[0].meters_per_pixel_y;
    out.height_min_m = lo;
    out.height_max_m = hi > lo ? hi : lo + 1.0;  // a flat export still decodes (to its one height)
    out.height_step_m = (out.height_max_m - out.height_min_m) / 65535.0;

    nlohmann::json tile_list = nlohmann::json::array();
    for (int ty = 0, t = 0; ty < plan.tiles_y; ++ty)
        for (int tx = 0; tx < plan.tiles_x; ++tx, ++t) {
            const Heightfield& field = tiles[t];
            const std::string path = stem + tileSuffix(plan, tx, ty) + ext;
            std::vector<uint16_t> samples(field.size());
            for (int y = 0; y < field.height; ++y) {
                const int row = plan.engine == Engine::Unity ? field.height - 1 - y : y;  // Unity reads row 0 as south
                for (int x = 0; x < field.width; ++x)
                    samples[size_t(row) * field.width + x] = static_cast<uint16_t>(
                        std::lround(std::clamp((field.at(x, y) - out.height_min_m) / out.height_step_m, 0.0, 65535.0)));
            }
            Status staged = ext == ".png"   ? stagePng16(transaction, path, field.width, field.height, 1, samples)
                            : ext == ".exr" ? stageHeightfieldExr(transaction, path, field)
                                            : transaction.stage(path, littleEndian16(samples));
            if (!staged) return staged;
            out.files.push_back(path);
            nlohmann::json entry = {{"file", detail::baseName(path)}, {"index", {tx, ty}},
                                    {"samples", {field.width, field.height}}};
            // Where the tile's north-west (Unity: south-west) corner goes, in the engine's units.
            const double east_m = double(tx) * plan.tile_step_x * out.spacing_x_m;
            const double south_m = double(ty) * plan.tile_step_y * out.spacing_y_m;
            if (plan.engine == Engine::Unreal) {
                entry["location_cm"] = {east_m * 100.0, south_m * 100.0};
            } else if (plan.engine == Engine::Unity) {
                const double north_m = double(plan.tiles_y - 1 - ty) * plan.tile_step_y * out.spacing_y_m;
                entry["position_m"] = {east_m, out.height_min_m, north_m};
            } else {  // Terrain3D centres an import on its position; Godot's +Z is south
                entry["import_position_m"] = {east_m + field.width * out.spacing_x_m / 2.0, 0.0,
                                              south_m + field.height * out.spacing_y_m / 2.0};
            }
            if (options.types) {
                auto types = options.types(plan.tile(tx, ty), options.level);
                if (!types) return types.status().withContext(path + " masks");
                TypeMaskOptions mask_options;
                mask_options.blur_radius = options.mask_blur;
                auto masks = stageTypeMasks(transaction, stem + "_", field.width, field.height, *types, options.type_names,
                                            mask_options, tileSuffix(plan, tx, ty));
                if (!masks) return masks.status();
                for (const std::string& m : *masks) {
                    entry["masks"].push_back(detail::baseName(m));
                    out.files.push_back(m);
                }
            }
            tile_list.push_back(std::move(entry));
        }

    const Heightfield& first = tiles[0];
    const std::string file = detail::baseName(out.files[0]);
    nlohmann::json json = {
        {"engine", engineName(plan.engine)},
        {"region", {plan.region.x, plan.region.y, plan.region.width, plan.region.height}},
        {"level", options.level},
        {"tiles", {plan.tiles_x, plan.tiles_y}},
        {"tile_samples", {plan.tile_width, plan.tile_height}},
        {"meters_per_pixel", {out.spacing_x_m, out.spacing_y_m}},
        {"height_min_m", out.height_min_m},
        {"height_max_m", out.height_max_m},
        {"height_step_m", out.height_step_m},
        {"decode", ext == ".exr" ? "float metres" : "height_m = height_min_m + value * height_step_m"},
        {"heightmaps", tile_list},
    };
    if (plan.engine == Engine::Unreal) {
        // Unreal: height_cm = location_z + (value - 32768) * scale_z / 128.
        const double scale_z = out.height_step_m * 100.0 * 128.0;
        const double location_z = (out.height_min_m + 32768.0 * out.height_step_m) * 100.0;
        const int section = plan.component_quads / 2;
        const int components_x = (plan.tile_width - 1) / plan.component_quads, components_y = (plan.tile_height - 1) / plan.component_quads;
        json["unreal"] = {{"scale", {out.spacing_x_m * 100.0, out.spacing_y_m * 100.0, scale_z}},
                          {"location_z_cm", location_z},
                          {"section_size_quads", section},
                          {"sections_per_component", "2x2"},
                          {"components", {components_x * plan.tiles_x, components_y * plan.tiles_y}}};
        if (plan.tiles_x * plan.tiles_y > 1) json["unreal"]["world_partition_region_size"] = components_x;
        out.summary = "Unreal Landscape > Import from File: " + file + (plan.tiles_x * plan.tiles_y > 1 ? " (tiled)" : "") + ", " +
                      std::to_string(plan.region.width) + "x" + std::to_string(plan.region.height) + " samples, section size " +
                      std::to_string(section) + "x" + std::to_string(section) + " quads, 2x2 sections per component, " +
                      std::to_string(components_x * plan.tiles_x) + "x" + std::to_string(components_y * plan.tiles_y) + " components" +
                      (plan.tiles_x * plan.tiles_y > 1 ? ", World Partition region size " + std::to_string(components_x) : "") +
                      format("; scale X %.4f Y %.4f Z %.4f; location Z %.2f cm", out.spacing_x_m * 100.0, out.spacing_y_m * 100.0,
                             scale_z, location_z);
    } else if (plan.engine == Engine::Unity) {
        const double width = (first.width - 1) * out.spacing_x_m, length = (first.height - 1) * out.spacing_y_m;
        json["unity"] = {{"resolution", first.width}, {"depth", 16}, {"byte_order", "Windows"}, {"flip_vertically", false},
                         {"terrain_size_m", {width, out.height_max_m - out.height_min_m, length}},
                         {"position_y_m", out.height_min_m}};
        out.summary = "Unity Terrain > Import Raw: " + file + (plan.tiles_x * plan.tiles_y > 1 ? " (tiles <stem>_<x>_<z>)" : "") +
                      ", depth 16 bit, resolution " + std::to_string(first.width) +
                      ", byte order Windows, flip vertically off; " +
                      format("terrain width %.3f m, length %.3f m, height %.3f m; position y %.3f m", width, length,
                             out.height_max_m - out.height_min_m, out.height_min_m);
    } else {
        json["godot"] = {{"vertex_spacing", out.spacing_x_m}, {"r16_range", {out.height_min_m, out.height_max_m}},
                         {"r16_size", {first.width, first.height}}, {"import_scale", 1.0}, {"import_offset", 0.0}};
        const auto& position = tile_list[0]["import_position_m"];
        out.summary = "Godot Terrain3D importer: " + file + (ext == ".exr" ? "" : ", r16_range " + format("(%.3f, %.3f)", out.height_min_m, out.height_max_m) +
                                                                                        ", r16_size (" + std::to_string(first.width) + ", " +
                                                                                        std::to_string(first.height) + ")") +
                      format(", import_position (%.1f, 0, %.1f); Terrain3D vertex_spacing %.4f", position[0].get<double>(),
                             position[2].get<double>(), out.spacing_x_m);
    }
    json["import"] = out.summary;
    out.json_path = stem + ".json";
    if (Status s = transaction.stage(out.json_path, detail::dumpJson(json, 1) + "\n"); !s) return s;
    out.files.push_back(out.json_path);
    return out;
}

}  // namespace terrasynth
