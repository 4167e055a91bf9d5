// terrasynth/engine_heightmap.h: heightmaps in the sizes, formats and scales that game engines'
// terrain importers take (docs/export.md, "Engine presets"): Unreal Engine Landscape, Unity Terrain,
// Godot's Terrain3D. Plain data in, files out; no engine code.
//
// Every preset writes 16-bit heights quantised over the exported range, so a height comes back
// through the stated scale within one step (range / 65535), plus the numbers to type into the
// engine's import dialog (EngineImport::summary, and a JSON file beside the heightmaps).
//
// Threading: the functions may be called from any thread; they call the sources from the calling
// thread only.
#pragma once

#include <string>
#include <vector>

#include "terrasynth/file_transaction.h"
#include "terrasynth/grid.h"
#include "terrasynth/status.h"

namespace terrasynth {

enum class Engine {
    // Landscape: square components of 63x63-quad sections, 2x2 sections each (127x127 quads for
    // the 8129 size), N x M components; sizes from the Landscape Technical Guide's table (127, 253,
    // 505, 1009, 2017, 4033, 8129 samples). 16-bit grayscale PNG or .r16 (little-endian), row 0 north.
    // Larger worlds: tiles of 2017 samples (16 x 16 components, one World Partition region of 16)
    // sharing their edge samples, <stem>_x<i>_y<j>, which Unreal's tiled import stitches.
    Unreal,
    // Terrain: square heightmaps of 2^n + 1 samples (33 .. 4097), RAW 16-bit little-endian
    // ("Windows" byte order), row 0 south ("Flip Vertically" off). Larger worlds: tiles of 4097
    // sharing their edge samples, <stem>_<x>_<z> (Terrain Tools' batch naming, z counting north).
    Unity,
    // Terrain3D: any size up to its 16384-sample world, .r16 (little-endian, row 0 north, decoded
    // through r16_range) or float .exr metres (builds with OpenEXR).
    Godot,
};

// "unreal", "unity" or "godot"; an error names the others.
Result<Engine> engineNamed(const std::string& name);

// Which samples a preset exports and how it cuts them into tiles.
struct EnginePlan {
    Engine engine = Engine::Unreal;
    PixelWindow region;              // the exported samples (global grid at the source's level)
    int tile_width = 0, tile_height = 0;  // samples per tile
    int tiles_x = 1, tiles_y = 1;
    int tile_step_x = 0, tile_step_y = 0;  // samples between tile origins (tile size - 1 where edges are shared)
    int component_quads = 0;         // Unreal: quads per component (126 or 254)
    PixelWindow tile(int tx, int ty) const;  // tile (tx, ty); ty = 0 is the northern row
};

// The engine's layout for `region` (at least 2x2 samples). `endless`: the source has heights beyond
// the region (a project's world), so the region grows east and south to the next engine size;
// otherwise (a heightmap file) it shrinks to the largest engine size inside it, an error when it is
// smaller than the smallest. Godot keeps the region as it is.
Result<EnginePlan> planEngineHeightmap(Engine engine, const PixelWindow& region, bool endless);

struct EngineExportOptions {
    // Heightmap path: its extension picks the format (Unreal .png or .r16, Unity .raw, Godot .r16 or
    // .exr); tiles, masks and the JSON take their names from its stem.
    std::string path;
    int level = 0;                   // source level the plan's region is on
    // Optional terrain types per pixel: one 8-bit splat mask per type beside each heightmap,
    // "<stem>_<type>[tile suffix].png", row 0 north, box-blurred by `mask_blur` pixels (0: hard).
    TypeSource types;
    std::vector<std::string> type_names;
    int mask_blur = 0;
};

struct EngineImport {
    std::vector<std::string> files;  // every file written: heightmaps, masks, then the JSON
    std::string json_path;           // <stem>.json: the plan, the scales, per tile its file and place
    double spacing_x_m = 0.0, spacing_y_m = 0.0;
    double height_min_m = 0.0, height_max_m = 0.0;  // what 16-bit 0 and 65535 decode to
    double height_step_m = 0.0;      // one 16-bit step, (max - min) / 65535
    std::string summary;             // one line with the numbers for the engine's import dialog
};

// Writes the heightmap(s) of `plan` from `heights`, the masks when `options.types` is set, and the
// JSON, into `transaction` (committed by the caller with any other outputs). Errors: the source's
// (with the tile), bad paths and extensions (naming them).
Result<EngineImport> stageEngineHeightmap(FileTransaction& transaction, const EnginePlan& plan,
                                          const HeightSource& heights, const EngineExportOptions& options);

}  // namespace terrasynth
