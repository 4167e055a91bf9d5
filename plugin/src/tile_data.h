// tile_data.h: the data model of one tile, the plain data it was built from (no OSG).
//
// A worker reads it from the height source (tile_builder.h), the render model is made from it, and
// it stays beside that render model, immutable (shared_ptr<const TileData>), for as long as the tile
// is resident. Whatever asks what the terrain *is* reads this, never the render geometry, whose
// vertices the mesh may reorder (optimize_order) and extend (skirts): TerrainNode::heightAt, a
// child's geomorph targets, and whether a rebuild after an edit changed anything.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "terrasynth/heightfield.h"
#include "terrasynth_plugin/tile_key.h"

namespace terrasynth::plugin {

struct TileData {
    TileKey key;
    // The read window as the source returned it: the tile's (tile_size + 1)^2 samples of key.level
    // plus an apron of `apron` samples on every side, row-major from the north-west corner.
    Heightfield heights;
    int apron = 0;
    int mesh_step = 1;       // the mesh has a vertex at every mesh_step-th sample of the tile
    double spacing_m = 0.0;  // metres between samples: the layout's spacing of key.level
    // World x of the tile's west edge and world y of its north edge (its sample (0, 0)), metres.
    double west_x = 0.0, north_y = 0.0;
    // The terrain type id of every tile sample ((tile_size + 1)^2, no apron, row-major) when the tile
    // was built with a type source; empty otherwise.
    std::vector<uint8_t> types;
    float min_height = 0.0f, max_height = 0.0f;  // over the tile's samples (apron excluded)
    // FNV-1a of the heights' bits (apron included), then of the types (hashTileData).
    uint64_t hash = 0;

    int tileSize() const { return heights.width - 1 - 2 * apron; }
    // Tile sample (col, row), (0, 0) at the north-west corner; the apron is at -apron..-1 and
    // tile_size + 1..tile_size + apron.
    float sample(int col, int row) const { return heights.at(col + apron, row + apron); }
    // Memory held by the samples and types.
    size_t bytes() const { return heights.heights.size() * sizeof(float) + types.size(); }
};

// 64-bit FNV-1a over the float bits of the field (and its size).
uint64_t hashHeights(const Heightfield& field);
// hashHeights of the heights, continued over the type ids.
uint64_t hashTileData(const Heightfield& heights, const std::vector<uint8_t>& types);

// Same samples, bit for bit, and same types: a rebuild equal to the resident tile is not swapped in.
bool sameSamples(const TileData& a, const TileData& b);

// Height at world (x, y) on the tile's mesh as drawn without geomorphing: in the grid cell under the
// point, on the triangles of terrasynth/mesh.h (each cell split along its north-east to south-west
// diagonal, heightOnGridCell). Points outside the tile take the nearest cell, extrapolated up to
// its edge.
float surfaceHeight(const TileData& tile, double world_x, double world_y);

// The parent level's samples under `child` (whose parent is `parent.key`): the (tile_size/2 + 1)^2
// samples of the parent that cover the child, spacing that of the parent's level. What geomorphing
// reads instead of asking the source for them again (bit for bit the same samples).
Heightfield parentSamples(const TileData& parent, const TileKey& child);

}  // namespace terrasynth::plugin
