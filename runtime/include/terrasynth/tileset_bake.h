// terrasynth/tileset_bake.h: baking a region of the world into a 3D Tiles 1.1 tileset of glTF tiles,
// sharded over processes or machines (docs/bake.md). Plain data in, files out; no OSG or GL.
//
// The tree. Tiles follow the quadtree of terrasynth/grid.h: a tile of LOD k (0 = finest) and index
// (i, j) covers level-0 samples [i*T*2^k, (i+1)*T*2^k] x [j*T*2^k, (j+1)*T*2^k], clipped to the
// region, and is a grid of T x T quads (fewer where clipped). LOD 0 meshes the level-0 heights at full
// resolution; LOD k >= 1 meshes every second sample of pyramid level k-1, so its vertices are real
// samples one level finer than its spacing and TileMesh::geometric_error_m (measured by the mesher
// against every level-(k-1) sample) is a true error. A tile's tileset geometricError adds its
// children's (errors accumulate towards the root, so they decrease strictly with depth on real
// relief; leaves are 0). Every tile hangs a skirt as deep as its own relief plus a margin, so
// neighbours of any LODs show no cracks (docs/bake.md, "Cracks").
//
// Frames. The tileset is in the world frame of terrasynth/grid.h (x east, y north, z up, metres,
// level-0 sample (0,0) at the origin); each .glb is glTF's Y-up turn of it (X east, Y up, Z south),
// which 3D Tiles turns back. The tileset is in local (engineering) coordinates: no geolocation.
//
// Files under the output folder: bake.json (the plan every shard checks it agrees with),
// tiles/<d>/<x>/<y>.glb (implicit-tiling coordinates: depth d from the root box, x east, y north),
// optional tiles/<d>/<x>/<y>.png|.f32|.tif heightmaps and tiles/<d>/<x>/<y>.mask_<type>.png splat
// masks beside the leaves, and after the merge tileset.json (+ subtrees/<d>/<x>/<y>.subtree for
// implicit tiling), and units/<lod>/<i>/<j>.json: per work unit, the size and digest of each of its
// files, written when the unit is done. Every file is written under a temporary name and renamed
// into place, so a file under its final name is always complete; a re-run skips tiles whose files
// match their unit's record (or, without one, are whole). Bakes of the same tiles by several
// processes at once (a requeued shard beside its first attempt) write the same bytes, so whichever
// rename lands last changes nothing.
//
// Sharding. The bake work is cut into units (a 2x2 block of leaves with their LOD-1 parent, which
// share one level-0 window, or one coarser tile), ordered along a Morton curve with every parent
// before its children, and split into N contiguous runs of equal synthesized area. Shard I of N
// bakes run I. The assignment depends only on the options, so any number of processes on any
// machines agree on it, and the files do not depend on the shard count or the thread count.
//
// Threading: bakeTiles runs `threads` workers that call the source concurrently (it must be
// thread-safe and bit-identical between overlapping windows, as terrasynth::Terrain is). The
// progress callback is called under a lock, from worker threads.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "terrasynth/grid.h"
#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"

namespace terrasynth {

// Heights (metres) of a window at a pyramid level and, when asked, the terrain type per sample
// (row-major, 255 = unknown). Same contract as HeightSource: exactly window-sized, thread-safe,
// bit-identical between overlapping windows.
struct BakeSamples {
    Heightfield heights;
    std::vector<uint8_t> types;  // empty unless want_types
};
using BakeSource = std::function<Result<BakeSamples>(const PixelWindow& window, int level, bool want_types)>;
// Adapts separate height and type sources (types may be empty when no masks are asked for).
BakeSource bakeSourceFrom(HeightSource heights, TypeSource types = {});

enum class TilesetLayout {
    Auto,      // explicit up to kImplicitFromDepth levels of tree, implicit beyond
    Explicit,  // every tile written out in tileset.json
    Implicit,  // 3D Tiles 1.1 implicit quadtree with subtree files (geometric error halves per level)
};
// Trees at least this deep (content levels plus the empty levels above the coarsest tiles) get
// implicit tiling under TilesetLayout::Auto.
constexpr int kImplicitFromDepth = 7;

enum class HeightmapFormat { None, Png16, Float32, GeoTiff };

struct BakeProgress {
    int64_t tiles_done = 0;     // baked or found complete, of this shard
    int64_t tiles_skipped = 0;  // of tiles_done, those already complete on disk
    int64_t tiles_total = 0;    // of this shard
    double seconds = 0.0;       // since bakeTiles started
};

struct BakeOptions {
    // Level-0 samples of the global grid to bake: W x H samples are (W-1) x (H-1) quads. W, H >= 2.
    PixelWindow region;
    // Quads per tile side, 2..4096.
    int tile_size = 256;
    // LODs (quadtree levels with content), 1..16; LOD k reads pyramid level k-1, so levels - 2 must
    // not exceed max_source_level.
    int levels = 4;
    // The coarsest pyramid level the source can give (the database's levels - 1).
    int max_source_level = 0;
    // Level-0 spacing in metres (the source's; recorded in the plan and the tileset).
    double meters_per_pixel = 1.0;
    // KHR_mesh_quantization: 16-bit positions on one grid per LOD (shared edges stay identical),
    // 8-bit normals, 16-bit indices (see GltfExportOptions::quantize).
    bool quantize = false;
    TilesetLayout layout = TilesetLayout::Auto;
    // Per-leaf heightmaps (T+1 samples a side, edges shared with neighbours) and hard 0/255 splat
    // masks, one PNG per terrain type, beside the leaf .glb files. Masks need type_names.
    HeightmapFormat heightmaps = HeightmapFormat::None;
    bool type_masks = false;
    std::vector<std::string> type_names;
    // Identifies the terrain (e.g. a hash of the project file): a bake into a folder whose plan names
    // another source is refused rather than mixing two terrains.
    std::string source_id;
    // This process bakes shard `shard_index` of `shard_count` (0 <= index < count).
    int shard_index = 0, shard_count = 1;
    // Worker threads; 0 = hardware concurrency.
    int threads = 0;
    std::function<void(const BakeProgress&)> progress;
};

// Checks the options (the message names the option): region size, tile size, levels against the
// source's levels, shard numbers, mask names.
Status checkBakeOptions(const BakeOptions& options);

// Tiles in the whole tree and in this shard (after checkBakeOptions succeeded).
struct BakeCounts {
    int64_t tiles = 0, shard_tiles = 0, units = 0, shard_units = 0;
    int depth = 0;  // levels of the tileset tree, empty ones above the coarsest tiles included
};
BakeCounts countBakeTiles(const BakeOptions& options);

// Creates `folder` (and its parents) when needed and writes its plan (bake.json), or checks that an
// existing plan is the same bake. Errors: folder not writable, a plan of another bake. Nothing is
// left behind on error (folders it created are removed).
Status prepareBakeFolder(const std::string& folder, const BakeOptions& options);

struct BakeStats {
    int64_t tiles_baked = 0, tiles_skipped = 0;
    int64_t bytes_written = 0;  // .glb and sidecar files written by this call
    double seconds = 0.0;
};
// Bakes this shard's tiles into a prepared folder, skipping tiles already complete and removing
// temporaries left by killed runs on this machine (never a live process's). Stops at the first error.
Result<BakeStats> bakeTiles(const std::string& folder, const BakeSource& source, const BakeOptions& options);

struct MergeStats {
    int64_t tiles = 0;
    int depth = 0;
    bool implicit = false;
    double root_geometric_error_m = 0.0;
    int64_t content_bytes = 0;  // all .glb files
};
// Every file the plan names that is missing or incomplete (relative paths), in tree order: tile
// files, and the unit records (units/<lod>/<i>/<j>.json) a shard writes once a unit is done. Cheap:
// nothing is read but .glb headers.
Result<std::vector<std::string>> findMissingTiles(const std::string& folder);
// Writes tileset.json (and subtree files) from the tiles on disk, after verifying every file of
// every tile against the record its shard wrote (size and FNV-1a digest) and every .glb's container
// (header, chunk lengths, a JSON chunk naming the tile it should be). Refuses, naming the files,
// when any is missing, incomplete or fails verification; writes nothing then, and `refused` (when
// given) lists those files (empty when the merge failed for another reason, e.g. an unwritable
// folder).
Result<MergeStats> mergeTileset(const std::string& folder, std::vector<std::string>* refused = nullptr);

}  // namespace terrasynth
