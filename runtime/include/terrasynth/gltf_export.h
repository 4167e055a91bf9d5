// terrasynth/gltf_export.h: exporting terrain as glTF 2.0 meshes, heightmaps and terrain-type masks
// (docs/export.md). Plain data in, files out; no OSG or GL.
//
// glTF frame: the region's north-west corner is the origin, X east, Y up, Z south, metres (the
// runtime's x east / y north / z up turned into glTF's Y-up, a proper rotation, so triangles keep
// their counter-clockwise front faces). One node per tile under a root node. With several LODs
// (LodLayout), either each LOD is a file of its own, or each tile node carries its finest LOD and
// the MSFT_lod extension names one node per coarser LOD (MSFT_screencoverage in its extras). Every
// file has a single buffer (the GLB BIN chunk, or <stem>.bin beside a .gltf).
//
// Threading: every function here may be called from any thread; exportGltf itself meshes tiles on
// `threads` worker threads and calls the sources from them concurrently (so sources must be
// thread-safe; terrasynth::Terrain::heights is).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"
#include "terrasynth/grid.h"

namespace terrasynth {

// Sources (HeightSource, TypeSource: terrasynth/grid.h) are asked for windows that may reach outside
// the requested export region by a one-pixel apron (for normals).

// A source over a heightfield in memory: pixel (x, y) of the global grid is field sample (x, y);
// windows reaching outside repeat the edge samples. `level` must be 0. The field is copied.
HeightSource heightSourceFromField(Heightfield field);
// Types per pixel from a synthesis coordinate map: type = exemplar_type[source_exemplar[p]], 255
// where the exemplar index is out of range (kNoExemplar).
std::vector<uint8_t> typesFromSources(const std::vector<uint8_t>& source_exemplar,
                                      const std::vector<int>& exemplar_type);

enum class LodMethod {
    // LOD k samples every 2^k-th pixel inside the tile and keeps every border sample, fanned into
    // the coarse interior: any mix of LODs between neighbours is crack-free. Fast. The default.
    StitchedGrid,
    // LOD k keeps 4^-k of the triangles through meshoptimizer with the border locked: also
    // crack-free, adapts to the relief, but about 10x slower and it leaves slivers along the border.
    Simplify,
};

// Where the coarser levels of detail go when there are several.
enum class LodLayout {
    // One file per LOD, each a whole terrain: `path` holds LOD 0, gltfLodPath(path, k) LOD k. What
    // tools that import every node (Blender 3.4) and engines that take LODs as separate meshes
    // (Unreal's LOD import, Unity's LODGroup) want. The default.
    Files,
    // One file: each tile node holds LOD 0 and names its coarser nodes through MSFT_lod. Those nodes
    // are outside the scene, so clients that ignore the extension draw LOD 0 only (three.js), but
    // importers that read every node (Blender 3.4) draw all LODs at once.
    MsftLod,
};

struct GltfExportOptions {
    // The samples to export (global pixel grid at `level`): a region of W x H samples becomes
    // (W-1) x (H-1) quads. Width and height >= 2.
    PixelWindow region;
    int level = 0;
    // Quads per tile side, 1..4096. Neighbouring tiles share their edge samples.
    int tile_size = 256;
    // Levels of detail per tile, 1..8 (LOD k has about 4^-k of the triangles).
    int lods = 1;
    LodMethod lod_method = LodMethod::StitchedGrid;
    LodLayout lod_layout = LodLayout::Files;
    // KHR_mesh_quantization (declared in extensionsRequired): positions as 16-bit integers on one
    // uniform grid shared by all tiles (so shared edges stay bit-identical), normals as normalized
    // 8-bit, uvs as normalized 16-bit, and every primitive kept under 65536 vertices so indices are
    // 16-bit. All vertex attributes 4-byte aligned.
    bool quantize = false;
    // COLOR_0 per vertex from a hypsometric tint over the region's height range, blended with a
    // colour per terrain type when `types` is set.
    bool vertex_colors = false;
    // > 0: embed a PNG base-colour texture of at most this many pixels per side with the same tint
    // (and types); TEXCOORD_0 then spans the whole region. 0 = none. At most 8192.
    int texture_size = 0;
    // Optional terrain types per pixel for colours and the texture.
    TypeSource types;
    // Worker threads for meshing; 0 = hardware concurrency.
    int threads = 0;
};

struct GltfLodStats {
    size_t vertices = 0, triangles = 0;
    float max_geometric_error_m = 0.0f;  // worst tile (TileMesh::geometric_error_m)
};

struct GltfExportStats {
    int tiles_x = 0, tiles_y = 0;
    std::vector<GltfLodStats> lods;      // per LOD, summed over tiles
    size_t primitives = 0;
    size_t json_bytes = 0, binary_bytes = 0;
    size_t file_bytes = 0;               // everything written (GLB, or .gltf + .bin), all LOD files
    std::vector<std::string> files;      // the glTF files written (one per LOD with LodLayout::Files)
    double quantum_m = 0.0;              // position quantisation step (quantized output), else 0
};

// Whether `path` names a glTF file: it ends in .glb or .gltf, in any letter case.
bool isGltfPath(const std::string& path);
// The file of LOD `lod` with LodLayout::Files: `path` itself for LOD 0, "<stem>_lod<k><.ext>" beside
// it for LOD k > 0 (terrain.glb -> terrain_lod1.glb).
std::string gltfLodPath(const std::string& path, int lod);

// Writes `path` (.glb binary, or .gltf JSON plus <stem>.bin beside it; with LodLayout::Files and
// several LODs also the gltfLodPath files) from the heights `source` gives for options.region.
// Files are written to temporaries and renamed into place. Errors: the source's error (with the
// window), bad options (message names the option), unwritable paths.
Result<GltfExportStats> exportGltf(const std::string& path, const HeightSource& source,
                                   const GltfExportOptions& options);
// The same, staged into `transaction` (.bin first, the .gltf that names it last) to be committed
// with other outputs (file_transaction.h).
Result<GltfExportStats> stageGltf(FileTransaction& transaction, const std::string& path, const HeightSource& source,
                                  const GltfExportOptions& options);
// Tiles of one export at most (each is a glTF node with its own meshes).
constexpr int64_t kMaxGltfTiles = 65536;

// Heightmap export, the format from the extension: .png (16-bit + JSON sidecar, readable as an
// exemplar), .f32/.raw (float32 + sidecar), .exr (when built with OpenEXR), .tif/.tiff (float32
// GeoTIFF written directly, no library needed: pixel-is-area, metres, a local projected frame whose
// origin is (origin_x_m, origin_y_m) at the north-west corner with y north). Errors name the path.
Status exportHeightmap(const std::string& path, const Heightfield& field, double origin_x_m = 0.0,
                       double origin_y_m = 0.0);
Status stageHeightmapExport(FileTransaction& transaction, const std::string& path, const Heightfield& field,
                            double origin_x_m = 0.0, double origin_y_m = 0.0);
// The same for a field holding the samples of `window` of the global grid (at the field's level):
// a GeoTIFF is placed in the world frame of grid.h, sample (x, y) at (x * spacing, -y * spacing),
// as `terrasynth synth` and `terrasynth export` place theirs.
Status exportHeightmap(const std::string& path, const Heightfield& field, const PixelWindow& window);
Status stageHeightmapExport(FileTransaction& transaction, const std::string& path, const Heightfield& field,
                            const PixelWindow& window);
// What exportHeightmap would say about `path`'s extension, without touching the disk.
Status checkHeightmapExportPath(const std::string& path);

struct TypeMaskOptions {
    // Box-blur radius in pixels; 0 = hard 0/255 masks. With blur the masks of all types still sum to
    // 255 at every pixel (largest-remainder rounding), ready for texture splatting.
    int blur_radius = 0;
};

// One 8-bit grayscale PNG per terrain type, "<prefix><type name>.png" (names sanitised to
// [A-Za-z0-9_-]), 255 where the pixel's type is that type. `types` is width*height type ids (see
// typesFromSources); pixels of unknown type (255) are 0 in every mask. Returns the paths written, in
// type order; types absent from the map still get an (all-zero) mask so splat channels are stable.
// The path writeTypeMasks writes the mask of type `index` to, with `suffix` before ".png".
std::string typeMaskPath(const std::string& prefix, const std::vector<std::string>& type_names, size_t index,
                         const std::string& suffix = "");
Result<std::vector<std::string>> writeTypeMasks(const std::string& prefix, int width, int height,
                                                const std::vector<uint8_t>& types,
                                                const std::vector<std::string>& type_names,
                                                const TypeMaskOptions& options = {});
// The same, staged; `name_suffix` goes before each mask's ".png" (a tile's "_x0_y0", so that engines
// see a tile set).
Result<std::vector<std::string>> stageTypeMasks(FileTransaction& transaction, const std::string& prefix, int width,
                                                int height, const std::vector<uint8_t>& types,
                                                const std::vector<std::string>& type_names,
                                                const TypeMaskOptions& options = {},
                                                const std::string& name_suffix = "");

}  // namespace terrasynth
