// terrasynth/grid.h: the global pixel grid every stage addresses, and the world frame around it.
//
// Pixels: level k of the pyramid is a grid of samples spaced 2^k times the level-0 spacing (the
// database's meters_per_pixel). A sample's integer coordinates (x, y) are global: x grows east,
// y grows south, and the grid is unbounded in every direction (int64), so any window of the world
// can be asked for and overlapping windows agree bit for bit.
//
// World frame (scene graphs, glTF before its Y-up turn, picking, collision): x east, y north, z up,
// metres, with level-0 sample (0, 0) at the origin. So sample (x, y) of level k sits at
// world (x * s_k, -y * s_k) with s_k = meters_per_pixel * 2^k, and a quadtree tile of T quads at
// level k, index (i, j), covers samples [i*T, i*T + T] x [j*T, j*T + T] (edges shared).
//
// Everything here is header-only plain data; no OSG, GL or OpenCL.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"

namespace terrasynth {

// A rectangle of the global pixel grid at some pyramid level (x east, y south).
struct PixelWindow {
    int64_t x = 0, y = 0;
    int width = 0, height = 0;

    bool empty() const { return width <= 0 || height <= 0; }
    bool contains(int64_t px, int64_t py) const { return px >= x && py >= y && px < x + width && py < y + height; }
    bool operator==(const PixelWindow& o) const {
        return x == o.x && y == o.y && width == o.width && height == o.height;
    }
    bool operator!=(const PixelWindow& o) const { return !(*this == o); }
};

// v / d rounded towards minus infinity (d > 0): the cell of a global coordinate, negative ones too.
inline int64_t floorDiv(int64_t v, int64_t d) { return v >= 0 ? v / d : -((d - 1 - v) / d); }

// The overlap of two windows; empty (width 0) when they do not overlap.
inline PixelWindow intersectWindows(const PixelWindow& a, const PixelWindow& b) {
    const int64_t x0 = a.x > b.x ? a.x : b.x, y0 = a.y > b.y ? a.y : b.y;
    const int64_t ax1 = a.x + a.width, bx1 = b.x + b.width, ay1 = a.y + a.height, by1 = b.y + b.height;
    const int64_t x1 = ax1 < bx1 ? ax1 : bx1, y1 = ay1 < by1 ? ay1 : by1;
    if (x1 <= x0 || y1 <= y0) return {x0, y0, 0, 0};
    return {x0, y0, static_cast<int>(x1 - x0), static_cast<int>(y1 - y0)};
}
// The smallest window holding both; an empty window does not count.
inline PixelWindow uniteWindows(const PixelWindow& a, const PixelWindow& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    const int64_t x0 = a.x < b.x ? a.x : b.x, y0 = a.y < b.y ? a.y : b.y;
    const int64_t ax1 = a.x + a.width, bx1 = b.x + b.width, ay1 = a.y + a.height, by1 = b.y + b.height;
    const int64_t x1 = ax1 > bx1 ? ax1 : bx1, y1 = ay1 > by1 ? ay1 : by1;
    return {x0, y0, static_cast<int>(x1 - x0), static_cast<int>(y1 - y0)};
}
// The window grown by `by` pixels on every side.
inline PixelWindow growWindow(const PixelWindow& w, int by) {
    return {w.x - by, w.y - by, w.width + 2 * by, w.height + 2 * by};
}

// The smallest window holding every sample where two planes over `extent` (row-major,
// extent.width * extent.height values each) differ; empty (width 0) when they are equal. What an
// edit changed, from the planes before and after it.
template <class T>
PixelWindow differingWindow(const PixelWindow& extent, const std::vector<T>& before, const std::vector<T>& after) {
    int64_t x0 = INT64_MAX, y0 = INT64_MAX, x1 = INT64_MIN, y1 = INT64_MIN;
    for (int y = 0; y < extent.height; ++y) {
        const T* a = before.data() + static_cast<size_t>(y) * extent.width;
        const T* b = after.data() + static_cast<size_t>(y) * extent.width;
        int first = 0, last = extent.width - 1;
        while (first <= last && a[first] == b[first]) ++first;
        if (first > last) continue;
        while (a[last] == b[last]) --last;
        x0 = x0 < extent.x + first ? x0 : extent.x + first;
        x1 = x1 > extent.x + last + 1 ? x1 : extent.x + last + 1;
        y0 = y0 < extent.y + y ? y0 : extent.y + y;
        y1 = extent.y + y + 1;
    }
    if (x1 <= x0) return {extent.x, extent.y, 0, 0};
    return {x0, y0, static_cast<int>(x1 - x0), static_cast<int>(y1 - y0)};
}

// Heights (metres) of `window` in the global grid of `level`: exactly window.width x window.height
// samples, spacing = level-0 spacing * 2^level. Implementations must be callable from several
// threads at once and return bit-identical samples for overlapping windows (otherwise neighbouring
// tiles would not meet).
using HeightSource = std::function<Result<Heightfield>(const PixelWindow& window, int level)>;
// Terrain type id per pixel of a window (width*height, row-major, 255 = unknown). Same contract.
using TypeSource = std::function<Result<std::vector<uint8_t>>(const PixelWindow& window, int level)>;

// Conversions between global pixel coordinates and the world frame for one level-0 spacing.
struct GridFrame {
    double meters_per_pixel = 1.0;  // level-0 spacing, > 0

    double spacing(int level) const { return std::ldexp(meters_per_pixel, level); }
    // World x (east) and y (north) of the (possibly fractional) sample position (px, py) at `level`.
    double worldX(double px, int level = 0) const { return px * spacing(level); }
    double worldY(double py, int level = 0) const { return -py * spacing(level); }
    // Fractional sample position at `level` of world (wx, wy); whole values are samples.
    double pixelX(double wx, int level = 0) const { return wx / spacing(level); }
    double pixelY(double wy, int level = 0) const { return -wy / spacing(level); }
};

}  // namespace terrasynth
