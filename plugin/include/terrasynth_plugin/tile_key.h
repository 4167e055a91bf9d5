// terrasynth_plugin/tile_key.h: addressing of the terrain quadtree.
//
// A tile at `level` k is the window of (tile_size + 1) samples of the global pixel grid of level k
// starting at (x * tile_size, y * tile_size): neighbours share their edge samples, and the four
// children of (k, x, y) are (k-1, 2x+i, 2y+j). Level 0 is the finest (the database spacing); level k
// has 2^k times that spacing. x grows east and y grows south, like pixels; the world frame of the
// scene graph is the one of terrasynth/grid.h (GridFrame): x east, y north, z up, metres, with
// global pixel (0, 0) of level 0 at the origin.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "terrasynth/grid.h"

namespace terrasynth::plugin {

struct TileKey {
    int level = 0;
    int64_t x = 0, y = 0;

    bool operator==(const TileKey& o) const { return level == o.level && x == o.x && y == o.y; }
    bool operator!=(const TileKey& o) const { return !(*this == o); }
    TileKey parent() const { return {level + 1, floorDiv2(x), floorDiv2(y)}; }
    TileKey child(int i, int j) const { return {level - 1, 2 * x + i, 2 * y + j}; }

private:
    static int64_t floorDiv2(int64_t v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); }
};

struct TileKeyHash {
    size_t operator()(const TileKey& k) const {
        uint64_t h = static_cast<uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= static_cast<uint64_t>(k.level) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return static_cast<size_t>(h);
    }
};

// Geometry of the quadtree in pixels and metres.
struct TileLayout {
    int tile_size = 256;            // quads per tile side; a tile has tile_size + 1 samples per side
    double meters_per_pixel = 1.0;  // level-0 spacing

    GridFrame frame() const { return {meters_per_pixel}; }
    double spacing(int level) const { return frame().spacing(level); }
    double tileMeters(int level) const { return spacing(level) * tile_size; }
    // The tile's samples in the global grid of its level (edges shared with neighbours).
    PixelWindow window(const TileKey& k) const {
        return {k.x * tile_size, k.y * tile_size, tile_size + 1, tile_size + 1};
    }
    // World x of the west edge and world y of the north edge, metres.
    double westX(const TileKey& k) const { return static_cast<double>(k.x) * tileMeters(k.level); }
    double northY(const TileKey& k) const { return -static_cast<double>(k.y) * tileMeters(k.level); }
    // The tile containing world point (wx, wy) at `level`.
    TileKey keyAt(double wx, double wy, int level) const {
        const double m = tileMeters(level);
        return {level, static_cast<int64_t>(std::floor(wx / m)), static_cast<int64_t>(std::floor(-wy / m))};
    }
};

}  // namespace terrasynth::plugin
