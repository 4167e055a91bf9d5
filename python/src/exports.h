// The exports of a project and of an edit session (export_heightmap, export_gltf, export_engine):
// the runtime's writers, given what `terrasynth export` gives them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "calls.h"
#include "terrasynth/grid.h"

namespace terrasynth::python {

// What an export reads: a project's terrain or an edit session's world.
struct ExportInput {
    HeightSource heights;
    TypeSource types;  // null: no terrain types (an edit session)
    std::vector<std::string> type_names;
    PixelWindow extent;  // the project's, level 0
};

// The region an export writes: `region` as given (samples of the grid at `level`), or the extent
// at that level (as `terrasynth export` without --region).
PixelWindow exportRegion(const ExportInput& input, const std::optional<WindowTuple>& region, int level);

void exportHeightmap(const ExportInput& input, const std::string& path, const std::optional<WindowTuple>& region,
                     int level);
py::dict exportGltf(const ExportInput& input, const std::string& path, const std::optional<WindowTuple>& region,
                    int level, int tile, int lods, const std::string& lod_method, const std::string& lod_layout,
                    bool quantize, bool colors, int texture);
py::dict exportEngine(const ExportInput& input, const std::string& preset, const std::string& path,
                      const std::optional<WindowTuple>& region, int level, int mask_blur);

// Adds export_heightmap, export_gltf and export_engine to `cls`, reading `input(self)`.
template <class Class, class Input>
void addExportMethods(Class& cls, Input input) {
    using Self = typename Class::type;
    using namespace pybind11::literals;
    cls.def(
        "export_heightmap",
        [input](Self& self, const std::string& path, std::optional<WindowTuple> region, int level) {
            exportHeightmap(input(self), path, region, level);
        },
        "path"_a, py::kw_only(), "region"_a = py::none(), "level"_a = 0,
        "Writes the heights of `region` (x, y, width, height samples of the grid at `level`; default: the "
        "extent) as `terrasynth export -o` does, the format from the extension: .tif/.tiff (float32 GeoTIFF "
        "in the local metric frame), .png (16-bit + JSON sidecar), .f32/.raw (float32 + sidecar), .exr.");
    cls.def(
        "export_gltf",
        [input](Self& self, const std::string& path, std::optional<WindowTuple> region, int level, int tile, int lods,
                const std::string& lod_method, const std::string& lod_layout, bool quantize, bool colors, int texture) {
            return exportGltf(input(self), path, region, level, tile, lods, lod_method, lod_layout, quantize, colors,
                              texture);
        },
        "path"_a, py::kw_only(), "region"_a = py::none(), "level"_a = 0, "tile"_a = 256, "lods"_a = 1,
        "lod_method"_a = "grid", "lod_layout"_a = "files", "quantize"_a = false, "colors"_a = false, "texture"_a = 0,
        "Writes a glTF 2.0 mesh (.glb or .gltf + .bin) of `region` (default: the extent) in tiles of `tile` "
        "quads with `lods` levels of detail, as `terrasynth export` does (docs/export.md). Returns the "
        "statistics: files, tiles, bytes, and per LOD vertices, triangles and geometric error.");
    cls.def(
        "export_engine",
        [input](Self& self, const std::string& preset, const std::string& path, std::optional<WindowTuple> region,
                int level, int mask_blur) { return exportEngine(input(self), preset, path, region, level, mask_blur); },
        "preset"_a, "path"_a, py::kw_only(), "region"_a = py::none(), "level"_a = 0, "mask_blur"_a = 0,
        "Writes a heightmap for a game engine's terrain importer, as `terrasynth export --preset` does: "
        "`preset` is 'unreal', 'unity' or 'godot'; the region grows to the engine's sizes; splat masks per "
        "terrain type beside it (projects), and <stem>.json with the import numbers. Returns the files and "
        "the numbers (summary, spacing, height range and step).");
}

}  // namespace terrasynth::python
