// The tree of a bake: which tiles exist, where their samples and files are, the Morton pre-order,
// the work units and how they are shared out between shards.
#include <algorithm>
#include <cmath>

#include "export/tileset_plan.h"

namespace terrasynth::bake_detail {

namespace {

IndexRange rangeOf(const PixelWindow& region, int tile, int lod) {
    // Tiles whose quads [i*span, (i+1)*span) meet the region's quads [x, x + width - 1).
    const int64_t span = int64_t(tile) << lod;
    IndexRange r;
    r.i0 = floorDiv(region.x, span);
    r.i1 = floorDiv(region.x + region.width - 2, span);
    r.j0 = floorDiv(region.y, span);
    r.j1 = floorDiv(region.y + region.height - 2, span);
    return r;
}

int ceilLog2(int64_t n) {
    int bits = 0;
    while ((int64_t(1) << bits) < n) ++bits;
    return bits;
}

// Interleaves x into the even bits and y into the odd bits (x is the low bit, as 3D Tiles' Morton
// index of a quadtree child wants).
uint64_t interleave(uint64_t x, uint64_t y) {
    auto spread = [](uint64_t v) {
        v &= 0xFFFFFFFFull;
        v = (v | (v << 16)) & 0x0000FFFF0000FFFFull;
        v = (v | (v << 8)) & 0x00FF00FF00FF00FFull;
        v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0Full;
        v = (v | (v << 2)) & 0x3333333333333333ull;
        v = (v | (v << 1)) & 0x5555555555555555ull;
        return v;
    };
    return spread(x) | (spread(y) << 1);
}

// `items` reordered by their keys (stable for equal keys).
template <class T>
std::vector<T> sortedByKeys(const std::vector<T>& items, const std::vector<std::pair<uint64_t, int>>& keys) {
    std::vector<size_t> order(items.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return keys[a] < keys[b]; });
    std::vector<T> sorted;
    sorted.reserve(items.size());
    for (size_t k : order) sorted.push_back(items[k]);
    return sorted;
}

}  // namespace

BakeTree::BakeTree(const BakeOptions& options)
    : region_(options.region), tile_(options.tile_size), levels_(options.levels), mpp_(options.meters_per_pixel) {
    for (int lod = 0; lod < levels_; ++lod) ranges_.push_back(rangeOf(region_, tile_, lod));
    const IndexRange& top = ranges_.back();
    empty_levels_ = ceilLog2(std::max(top.countI(), top.countJ()));
}

bool BakeTree::exists(const TileKey& t) const {
    if (t.lod < 0 || t.lod >= levels_) return false;
    const IndexRange& r = ranges_[t.lod];
    return t.i >= r.i0 && t.i <= r.i1 && t.j >= r.j0 && t.j <= r.j1;
}

SampleSpan BakeTree::samples(const TileKey& t) const {
    const int level = sourceLevel(t.lod);
    const int64_t per_tile = int64_t(tile_) << (t.lod - level);  // source samples across the tile
    const int64_t scale = int64_t(1) << level;
    SampleSpan s;
    s.x0 = std::max(t.i * per_tile, floorDiv(region_.x, scale));
    s.x1 = std::min((t.i + 1) * per_tile, ceilDiv(region_.x + region_.width - 1, scale));
    s.y0 = std::max(t.j * per_tile, floorDiv(region_.y, scale));
    s.y1 = std::min((t.j + 1) * per_tile, ceilDiv(region_.y + region_.height - 1, scale));
    return s;
}

ImplicitCoord BakeTree::implicitOf(const TileKey& t) const {
    const IndexRange& top = ranges_.back();
    const int below_top = levels_ - 1 - t.lod;
    ImplicitCoord c;
    c.depth = empty_levels_ + below_top;
    const int64_t row = t.j - top.j0 * (int64_t(1) << below_top);  // 0 at the root box's north edge
    c.x = t.i - top.i0 * (int64_t(1) << below_top);
    c.y = (int64_t(1) << c.depth) - 1 - row;
    return c;
}

TileKey BakeTree::tileAt(const ImplicitCoord& c) const {
    const IndexRange& top = ranges_.back();
    const int below_top = c.depth - empty_levels_;
    TileKey t;
    t.lod = levels_ - 1 - below_top;
    t.i = c.x + top.i0 * (int64_t(1) << below_top);
    t.j = ((int64_t(1) << c.depth) - 1 - c.y) + top.j0 * (int64_t(1) << below_top);
    return t;
}

std::string BakeTree::tilePath(const TileKey& t, const std::string& extension) const {
    const ImplicitCoord c = implicitOf(t);
    return "tiles/" + std::to_string(c.depth) + "/" + std::to_string(c.x) + "/" + std::to_string(c.y) + extension;
}

uint64_t BakeTree::mortonKey(const TileKey& t) const {
    // Position of the tile's north-west leaf inside the root box, rows counted from the north.
    const IndexRange& top = ranges_.back();
    const int below_top = levels_ - 1 - t.lod;
    const int64_t col = t.i - top.i0 * (int64_t(1) << below_top);
    const int64_t row = t.j - top.j0 * (int64_t(1) << below_top);
    return interleave(static_cast<uint64_t>(col) << t.lod, static_cast<uint64_t>(row) << t.lod);
}

std::vector<TileKey> BakeTree::allTiles() const {
    std::vector<TileKey> tiles;
    for (int lod = levels_ - 1; lod >= 0; --lod) {
        const IndexRange& r = ranges_[lod];
        for (int64_t j = r.j0; j <= r.j1; ++j)
            for (int64_t i = r.i0; i <= r.i1; ++i) tiles.push_back({lod, i, j});
    }
    std::vector<std::pair<uint64_t, int>> keys(tiles.size());
    for (size_t k = 0; k < tiles.size(); ++k) keys[k] = {mortonKey(tiles[k]), -tiles[k].lod};
    return sortedByKeys(tiles, keys);
}

void BakeTree::rootExtent(double* west, double* south, double* east, double* north) const {
    const IndexRange& top = ranges_.back();
    const double cell = double(int64_t(tile_) << (levels_ - 1)) * mpp_;
    const double cells = std::ldexp(1.0, empty_levels_);
    *west = top.i0 * cell;
    *east = (top.i0 + cells) * cell;
    *north = -top.j0 * cell;
    *south = -(top.j0 + cells) * cell;
}

std::vector<TileKey> unitTiles(const BakeTree& tree, const BakeUnit& unit) {
    std::vector<TileKey> tiles;
    const TileKey self{unit.lod, unit.i, unit.j};
    if (tree.exists(self)) tiles.push_back(self);
    if (unit.lod != 1) return tiles;
    for (int b = 0; b < 2; ++b)  // Z order: north-west, north-east, south-west, south-east
        for (int a = 0; a < 2; ++a) {
            const TileKey leaf{0, 2 * unit.i + a, 2 * unit.j + b};
            if (tree.exists(leaf)) tiles.push_back(leaf);
        }
    return tiles;
}

PixelWindow unitWindow(const BakeTree& tree, const BakeUnit& unit) {
    const SampleSpan s = tree.samples({unit.lod, unit.i, unit.j});
    return growWindow({s.x0, s.y0, s.quadsX() + 1, s.quadsY() + 1}, kApron);
}

std::vector<BakeUnit> orderedUnits(const BakeTree& tree) {
    std::vector<BakeUnit> units;
    // Blocks exist wherever leaves do, also in a one-level tree (they then carry no LOD-1 tile).
    const IndexRange blocks = rangeOf(tree.region(), tree.tileSize(), 1);
    for (int64_t j = blocks.j0; j <= blocks.j1; ++j)
        for (int64_t i = blocks.i0; i <= blocks.i1; ++i) units.push_back({1, i, j, 0.0});
    for (int lod = 2; lod < tree.levels(); ++lod) {
        const IndexRange& r = tree.range(lod);
        for (int64_t j = r.j0; j <= r.j1; ++j)
            for (int64_t i = r.i0; i <= r.i1; ++i) units.push_back({lod, i, j, 0.0});
    }
    std::vector<std::pair<uint64_t, int>> keys;
    std::vector<BakeUnit> kept;
    for (BakeUnit& u : units) {
        const std::vector<TileKey> tiles = unitTiles(tree, u);
        if (tiles.empty()) continue;
        const PixelWindow w = unitWindow(tree, u);
        u.weight = double(w.width) * w.height;
        for (const TileKey& t : tiles) {
            const SampleSpan s = tree.samples(t);
            const int step = BakeTree::meshStep(t.lod);
            u.weight += double(s.quadsX() / step + 1) * (s.quadsY() / step + 1);
        }
        keys.push_back({tree.mortonKey(tiles.front()), -tiles.front().lod});
        kept.push_back(u);
    }
    return sortedByKeys(kept, keys);
}

void shardRange(const std::vector<BakeUnit>& units, int index, int count, size_t* first, size_t* last) {
    double total = 0.0;
    for (const BakeUnit& u : units) total += u.weight;
    // A unit belongs to the shard its weight's midpoint falls in, so runs are contiguous and each
    // is within half a unit of total / count.
    *first = units.size(), *last = units.size();
    double before = 0.0;
    bool found = false;
    for (size_t k = 0; k < units.size(); ++k) {
        const double mid = before + 0.5 * units[k].weight;
        const int shard = std::min(count - 1, static_cast<int>(std::floor(mid / total * count)));
        before += units[k].weight;
        if (shard == index && !found) *first = k, found = true;
        if (shard > index) {
            *last = k;
            break;
        }
    }
    if (!found) *first = *last = 0;
}

float skirtDepth(const Heightfield& field, int border, double vertex_spacing_m) {
    float lo = INFINITY, hi = -INFINITY;
    for (int y = border; y < field.height - border; ++y)
        for (int x = border; x < field.width - border; ++x) lo = std::min(lo, field.at(x, y)), hi = std::max(hi, field.at(x, y));
    const double relief = std::max(0.0, double(hi) - lo);
    // The margin covers neighbours meshed from another pyramid level, whose edge may dip below this
    // tile's lowest sample (docs/bake.md, "Cracks").
    return static_cast<float>(relief + std::max(0.25 * relief, 2.0 * vertex_spacing_m));
}

}  // namespace terrasynth::bake_detail
