// Private pieces of the tileset bake (runtime/src/export/tileset_*.cpp): the tree of tiles, the work
// units and their shard assignment, one tile's glTF file, the plan file and the merged tileset.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "terrasynth/grid.h"
#include "terrasynth/mesh.h"
#include "terrasynth/tileset_bake.h"

namespace terrasynth::bake_detail {

inline int64_t ceilDiv(int64_t a, int64_t b) { return -floorDiv(-a, b); }

// A tile of the grid.h quadtree: LOD `lod` (0 = finest), index (i, j) at pyramid level `lod`.
struct TileKey {
    int lod = 0;
    int64_t i = 0, j = 0;
    bool operator==(const TileKey& o) const { return lod == o.lod && i == o.i && j == o.j; }
};

// Implicit-tiling coordinates: depth from the root box, x east, y north (3D Tiles' box axes).
struct ImplicitCoord {
    int depth = 0;
    int64_t x = 0, y = 0;
};

// Inclusive sample ranges at some pyramid level.
struct SampleSpan {
    int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int quadsX() const { return static_cast<int>(x1 - x0); }
    int quadsY() const { return static_cast<int>(y1 - y0); }
};

struct IndexRange {
    int64_t i0 = 0, i1 = -1, j0 = 0, j1 = -1;  // inclusive
    int64_t countI() const { return i1 - i0 + 1; }
    int64_t countJ() const { return j1 - j0 + 1; }
};

// The tiles of a bake (options already checked) and where each one lives.
class BakeTree {
public:
    explicit BakeTree(const BakeOptions& options);

    int levels() const { return levels_; }
    int tileSize() const { return tile_; }
    double metersPerPixel() const { return mpp_; }
    const PixelWindow& region() const { return region_; }
    // Tiles of one LOD whose quads meet the region's quads.
    const IndexRange& range(int lod) const { return ranges_[lod]; }
    bool exists(const TileKey& t) const;
    // Levels of the tree without content above the coarsest LOD, so that one root box holds it all.
    int emptyLevels() const { return empty_levels_; }
    int depth() const { return empty_levels_ + levels_; }

    // The pyramid level a LOD's mesh samples, and its grid step there.
    static int sourceLevel(int lod) { return lod == 0 ? 0 : lod - 1; }
    static int meshStep(int lod) { return lod == 0 ? 1 : 2; }
    // The tile's samples at its source level, clipped to the region (rounded outwards there).
    SampleSpan samples(const TileKey& t) const;

    ImplicitCoord implicitOf(const TileKey& t) const;
    // The content tile at implicit coordinates (depth >= emptyLevels()).
    TileKey tileAt(const ImplicitCoord& c) const;
    // "tiles/<d>/<x>/<y>" + extension, relative to the output folder.
    std::string tilePath(const TileKey& t, const std::string& extension) const;
    // Pre-order Morton key: parents before children, siblings in Z order.
    uint64_t mortonKey(const TileKey& t) const;
    // Every tile, in Morton pre-order.
    std::vector<TileKey> allTiles() const;

    // The root box in world metres (x east, y north): west, south, east, north.
    void rootExtent(double* west, double* south, double* east, double* north) const;

private:
    PixelWindow region_;
    int tile_ = 256, levels_ = 1, empty_levels_ = 0;
    double mpp_ = 1.0;
    std::vector<IndexRange> ranges_;
};

// A unit of work: lod 1 = the 2x2 leaves of LOD-1 tile (i, j) together with that tile (when the tree
// has LOD 1), all meshed from one level-0 window; lod >= 2 = that one tile.
struct BakeUnit {
    int lod = 1;
    int64_t i = 0, j = 0;
    double weight = 0.0;  // synthesized samples + meshed vertices
};
constexpr int kApron = 2;  // samples around a unit's window, for central-difference normals at step 2

std::vector<BakeUnit> orderedUnits(const BakeTree& tree);
// [first, last) of the units that shard `index` of `count` bakes: contiguous runs of equal weight.
void shardRange(const std::vector<BakeUnit>& units, int index, int count, size_t* first, size_t* last);
// The existing tiles a unit produces, coarsest first.
std::vector<TileKey> unitTiles(const BakeTree& tree, const BakeUnit& unit);
// The window the unit synthesizes (at level sourceLevel(unit lod)), apron included.
PixelWindow unitWindow(const BakeTree& tree, const BakeUnit& unit);

// The plan file (bake.json): the options that decide the output, canonical text.
std::string planText(const BakeOptions& options);
Result<BakeOptions> readPlan(const std::string& folder);
constexpr const char* kPlanFile = "bake.json";

// What the merge needs from a tile, kept in the .glb's root-node extras ("terrasynth_tile").
struct TileRecord {
    TileKey key;
    double own_error_m = 0.0;  // the mesher's, for this tile alone
    double bounds[6] = {0, 0, 0, 0, 0, 0};  // world x, y, z min then max, of the file's vertices
    int64_t file_bytes = 0;
};

// Meshes and writes one tile's .glb (atomically). `field` is the tile's samples at its source level
// with a `border` apron; the tile's north-west sample sits at source-level pixel (span.x0, span.y0).
Result<TileRecord> writeTileGlb(const std::string& path, const BakeTree& tree, const TileKey& key,
                                const Heightfield& field, int border, bool quantize);
// The record of a .glb held in memory, after checking the whole container: header magic, version
// 2 and length equal to the size, a JSON chunk then a BIN chunk whose lengths (multiples of 4) end
// exactly at the end of the file, the JSON bounded (limits.h) and naming a terrasynth tile, its
// buffer inside the BIN chunk. Errors name `path` and what is wrong.
Result<TileRecord> tileRecordFromGlb(const std::string& bytes, const std::string& path);
// True when `path` is a whole GLB (header length equals the file size).
bool glbComplete(const std::string& path);
// A tile's files relative to the output folder (heightmap, sidecar, masks for leaves), the .glb last.
std::vector<std::string> tileFiles(const BakeTree& tree, const BakeOptions& options, const TileKey& t);
// Every file present, the .glb whole.
bool tileFilesComplete(const std::string& folder, const std::vector<std::string>& files);

// ---- Unit records (tileset_records.cpp) ----
// units/<lod>/<i>/<j>.json, written when a unit's tiles are all on disk: every file of its tiles
// (tileFiles order) with its size and FNV-1a digest as found there. A re-run trusts a tile only
// when its files match the record, and the merge verifies every file against it.
struct FileDigest {
    int64_t bytes = 0;
    uint64_t digest = 0;
};
using RecordedFiles = std::map<std::string, FileDigest>;  // by path relative to the folder
std::string unitRecordPath(const BakeUnit& unit);
// The unit whose work produces tile `t`.
BakeUnit unitOf(const TileKey& t);
// The unit's record, checked: format, and exactly the files of the unit's tiles. Errors name the
// record and the field (a missing record is an error too).
Result<RecordedFiles> readUnitRecord(const std::string& folder, const BakeTree& tree, const BakeOptions& options,
                                     const BakeUnit& unit);
// Writes the unit's record (atomically): digests from `known` where given, else read from disk.
Status writeUnitRecord(const std::string& folder, const BakeTree& tree, const BakeOptions& options, const BakeUnit& unit,
                       const RecordedFiles& known);
// Reads one file of tile `tile` and checks it: against `recorded` (null: nothing recorded yet)
// in size and digest, and a .glb's container and tile (its record into `glb_record` when given).
// Errors name the file and the problem. Returns what was found.
Result<FileDigest> verifyTileFile(const std::string& folder, const std::string& file, const TileKey& tile,
                                  const FileDigest* recorded, TileRecord* glb_record);

// The skirt of a tile: its relief plus a margin, so that any neighbour's edge lies above its foot.
float skirtDepth(const Heightfield& field, int border, double vertex_spacing_m);

}  // namespace terrasynth::bake_detail
