#include "synth/coherence_fields.h"

namespace terrasynth::synth {
namespace {

// The 2x2 rule of s5.3: Frozen if any child is frozen, else the most frequent (ties: the freer).
uint8_t reduce(uint8_t a, uint8_t b, uint8_t c, uint8_t d) {
    int counts[3] = {0, 0, 0};
    ++counts[a], ++counts[b], ++counts[c], ++counts[d];
    if (counts[0] > 0) return static_cast<uint8_t>(Coherence::Frozen);
    return static_cast<uint8_t>(counts[1] > counts[2] ? Coherence::Coherent : Coherence::Free);
}

}  // namespace

std::vector<uint8_t> coherenceCodes(const CoherenceMap* map, int level, const LevelRegion& region) {
    std::vector<uint8_t> codes(region.pixels(), static_cast<uint8_t>(map ? map->outside : Coherence::Coherent));
    if (!map || map->width == 0) return codes;
    // Level-0 codes over the map's rectangle grown to whole level-`level` blocks (outside -> the
    // map's outside code), then reduced level by level: one pass per level, no recursion.
    const int64_t cell = int64_t(1) << level;
    const int64_t bx0 = (map->x >= 0 ? map->x / cell : -((-map->x + cell - 1) / cell));
    const int64_t by0 = (map->y >= 0 ? map->y / cell : -((-map->y + cell - 1) / cell));
    const int64_t bx1 = (map->x + map->width + cell - 1) / cell, by1 = (map->y + map->height + cell - 1) / cell;
    int64_t w = (bx1 - bx0) * cell, h = (by1 - by0) * cell;
    std::vector<uint8_t> grid(static_cast<size_t>(w * h), static_cast<uint8_t>(map->outside));
    for (int y = 0; y < map->height; ++y)
        for (int x = 0; x < map->width; ++x)
            grid[static_cast<size_t>((map->y + y - by0 * cell) * w + (map->x + x - bx0 * cell))] =
                static_cast<uint8_t>(map->weights[static_cast<size_t>(y) * map->width + x]);
    for (int l = 0; l < level; ++l) {
        const int64_t nw = w / 2, nh = h / 2;
        std::vector<uint8_t> next(static_cast<size_t>(nw * nh));
        for (int64_t y = 0; y < nh; ++y)
            for (int64_t x = 0; x < nw; ++x)
                next[y * nw + x] = reduce(grid[(2 * y) * w + 2 * x], grid[(2 * y) * w + 2 * x + 1],
                                          grid[(2 * y + 1) * w + 2 * x], grid[(2 * y + 1) * w + 2 * x + 1]);
        grid.swap(next);
        w = nw, h = nh;
    }
    for (int y = 0; y < region.height; ++y) {
        const int64_t gy = region.y + y - by0;
        if (gy < 0 || gy >= h) continue;
        for (int x = 0; x < region.width; ++x) {
            const int64_t gx = region.x + x - bx0;
            if (gx >= 0 && gx < w) codes[static_cast<size_t>(y) * region.width + x] = grid[gy * w + gx];
        }
    }
    return codes;
}

PassHistory previousPass(const SynthesisHistory* history, int level, int pass, const LevelRegion& region) {
    PassHistory out;
    if (!history || level >= static_cast<int>(history->levels.size())) return out;
    const SynthesisHistory::Level& l = history->levels[level];
    if (pass >= static_cast<int>(l.passes.size()) || l.width == 0) return out;
    const SynthesisHistory::Pass& p = l.passes[pass];
    out.index.assign(region.pixels(), kNoPrevious);
    out.v.assign(region.pixels(), 0.0f);
    for (int y = 0; y < region.height; ++y) {
        const int hy = region.y + y - l.y;
        if (hy < 0 || hy >= l.height) continue;
        for (int x = 0; x < region.width; ++x) {
            const int hx = region.x + x - l.x;
            if (hx < 0 || hx >= l.width) continue;
            const size_t from = static_cast<size_t>(hy) * l.width + hx, to = static_cast<size_t>(y) * region.width + x;
            out.index[to] = p.index[from];
            out.v[to] = p.v[from];
        }
    }
    return out;
}

}  // namespace terrasynth::synth

namespace terrasynth {

size_t SynthesisHistory::memoryBytes() const {
    size_t total = 0;
    for (const Level& l : levels)
        for (const Pass& p : l.passes) total += p.index.size() * sizeof(uint32_t) + p.v.size() * sizeof(float);
    return total;
}

}  // namespace terrasynth
