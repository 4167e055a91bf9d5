#include "exports.h"

#include <algorithm>

#include <pybind11/stl.h>

#include "terrasynth/engine_heightmap.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/gltf_export.h"

namespace terrasynth::python {

using namespace pybind11::literals;

PixelWindow exportRegion(const ExportInput& input, const std::optional<WindowTuple>& region, int level) {
    checkNumber("level", level, ranges::kOutputLevel);
    if (region) {
        const auto& [x, y, width, height] = *region;
        return checkedWindow(x, y, width, height, /*min_side=*/2);
    }
    PixelWindow extent = input.extent;  // the extent shrinks with the level
    extent.x >>= level, extent.y >>= level;
    extent.width = std::max(2, extent.width >> level), extent.height = std::max(2, extent.height >> level);
    return extent;
}

void exportHeightmap(const ExportInput& input, const std::string& path, const std::optional<WindowTuple>& region,
                     int level) {
    const PixelWindow window = exportRegion(input, region, level);
    check(withoutGil([&]() -> Status {
        if (Status s = checkHeightmapExportPath(path); !s) return s;
        auto field = input.heights(window, level);
        if (!field) return field.status();
        return exportHeightmap(path, *field, window);
    }));
}

py::dict exportGltf(const ExportInput& input, const std::string& path, const std::optional<WindowTuple>& region,
                    int level, int tile, int lods, const std::string& lod_method, const std::string& lod_layout,
                    bool quantize, bool colors, int texture) {
    checkNumber("tile", tile, ranges::kGltfTileQuads);
    checkNumber("lods", lods, ranges::kGltfLods);
    checkNumber("texture", texture, ranges::kTextureSize);
    GltfExportOptions options;
    options.region = exportRegion(input, region, level);
    options.level = level;
    options.tile_size = tile;
    options.lods = lods;
    if (lod_method == "simplify") options.lod_method = LodMethod::Simplify;
    else if (lod_method != "grid") throw py::value_error("lod_method: expected 'grid' or 'simplify', got '" + lod_method + "'");
    if (lod_layout == "msft") options.lod_layout = LodLayout::MsftLod;
    else if (lod_layout != "files") throw py::value_error("lod_layout: expected 'files' or 'msft', got '" + lod_layout + "'");
    options.quantize = quantize;
    options.vertex_colors = colors;
    options.texture_size = texture;
    if (colors || texture > 0) options.types = input.types;
    const GltfExportStats stats = take(withoutGil([&]() -> Result<GltfExportStats> {
        FileTransaction transaction;
        auto staged = stageGltf(transaction, path, input.heights, options);
        if (!staged) return staged;
        if (Status s = transaction.commit(); !s) return s;
        return staged;
    }));
    py::list per_lod;
    for (const GltfLodStats& lod : stats.lods)
        per_lod.append(py::dict("vertices"_a = lod.vertices, "triangles"_a = lod.triangles,
                                "max_geometric_error_m"_a = lod.max_geometric_error_m));
    return py::dict("files"_a = stats.files, "tiles"_a = py::make_tuple(stats.tiles_x, stats.tiles_y),
                    "file_bytes"_a = stats.file_bytes, "json_bytes"_a = stats.json_bytes,
                    "binary_bytes"_a = stats.binary_bytes, "lods"_a = per_lod);
}

py::dict exportEngine(const ExportInput& input, const std::string& preset, const std::string& path,
                      const std::optional<WindowTuple>& region, int level, int mask_blur) {
    checkNumber("mask_blur", mask_blur, ranges::kMaskBlur);
    const PixelWindow window = exportRegion(input, region, level);
    const EngineImport written = take(withoutGil([&]() -> Result<EngineImport> {
        auto engine = engineNamed(preset);
        if (!engine) return engine.status().withContext("preset");
        // A project's world goes on beyond the region: it grows to the engine's next size.
        auto plan = planEngineHeightmap(*engine, window, /*endless=*/true);
        if (!plan) return plan.status().withContext("preset " + preset);
        EngineExportOptions options;
        options.path = path;
        options.level = level;
        options.types = input.types;
        options.type_names = input.type_names;
        options.mask_blur = mask_blur;
        FileTransaction transaction;
        auto staged = stageEngineHeightmap(transaction, *plan, input.heights, options);
        if (!staged) return staged;
        if (Status s = transaction.commit(); !s) return s;
        return staged;
    }));
    return py::dict("files"_a = written.files, "json_path"_a = written.json_path, "summary"_a = written.summary,
                    "spacing_m"_a = py::make_tuple(written.spacing_x_m, written.spacing_y_m),
                    "height_min_m"_a = written.height_min_m, "height_max_m"_a = written.height_max_m,
                    "height_step_m"_a = written.height_step_m);
}

}  // namespace terrasynth::python
