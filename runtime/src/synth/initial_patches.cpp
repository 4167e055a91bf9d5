#include "synth/initial_patches.h"

#include <algorithm>
#include <string>
#include <utility>

#include "constraints/constraint_fields.h"
#include "core/hash.h"
#include "synth/synthesis_plan.h"
#include "terrasynth/status.h"

namespace terrasynth::synth {

int automaticCoarsestLevel(const ExemplarDatabase& db) {
    const std::vector<AtlasRect>& base = db.levels[0].rects;
    size_t total = 0;
    for (const AtlasRect& r : base) total += static_cast<size_t>(r.width) * r.height;
    for (int level = db.levelCount() - 1; level > 0; --level) {
        size_t large = 0;
        const std::vector<AtlasRect>& rects = db.levels[level].rects;
        for (size_t e = 0; e < rects.size() && e < base.size(); ++e)
            if (std::min(rects[e].width, rects[e].height) >= kMinCoarsestSide)
                large += static_cast<size_t>(base[e].width) * base[e].height;
        if (2 * large >= total) return level;
    }
    return 0;
}

int shareBlockSide(int level) {
    TERRASYNTH_REQUIRE(level >= 0, "shareBlockSide: negative level");
    return level >= 30 ? kShareCellsPerSide : std::max(kShareCellsPerSide, kShareBlockSide0 >> level);
}

std::vector<int> entryLevels(const ExemplarDatabase& db, int coarsest) {
    TERRASYNTH_REQUIRE(coarsest >= 0 && coarsest < db.levelCount(), "entryLevels: level outside the database");
    auto side = [&](int level, size_t e) {
        const AtlasRect& r = db.levels[level].rects[e];
        return std::min(r.width, r.height);
    };
    const size_t count = db.levels[coarsest].rects.size();
    bool any_large = false;
    for (size_t e = 0; e < count; ++e) any_large = any_large || side(coarsest, e) >= kMinCoarsestSide;
    // Without any exemplar that large, each enters where it first has interior pixels to copy.
    const int least_side = any_large ? kLateEntrySide : 2 * kInteriorMargin + 1;
    std::vector<int> entry(count, -1);
    for (size_t e = 0; e < count; ++e) {
        if (side(coarsest, e) >= kMinCoarsestSide) {
            entry[e] = coarsest;
            continue;
        }
        int level = coarsest;
        while (level > 0 && side(level, e) < least_side) --level;
        if (side(level, e) > 2 * kInteriorMargin) entry[e] = level;
    }
    return entry;
}

Result<std::vector<int>> startingEntryLevels(const ExemplarDatabase& db, int coarsest) {
    std::vector<int> entry = entryLevels(db, coarsest);
    if (!entersAt(entry, coarsest))
        return Status::error("database level " + std::to_string(coarsest) + " has no exemplar with interior pixels");
    return entry;
}

bool entersAt(const std::vector<int>& entry_levels, int level) {
    return std::find(entry_levels.begin(), entry_levels.end(), level) != entry_levels.end();
}

uint32_t shareSalt(uint32_t seed) { return core::levelSalt(seed, 0, 15); }

namespace {

// Cell (x, y) of step d of the Hilbert curve over an n x n grid (n a power of two): consecutive
// steps are 4-neighbours, and any run of steps stays compact.
void hilbertCell(int n, int d, int& x, int& y) {
    x = y = 0;
    for (int s = 1, t = d; s < n; s *= 2, t /= 4) {
        const int rx = 1 & (t / 2), ry = 1 & (t ^ rx);
        if (ry == 0) {
            if (rx == 1) x = s - 1 - x, y = s - 1 - y;
            std::swap(x, y);
        }
        x += s * rx;
        y += s * ry;
    }
}

// One block: the exemplars in a random order, their weights laid end to end over the curve's
// kShareCellsPerBlock steps, each step taking the exemplar under its point (one random offset for
// the block, so a run is the floor or the ceiling of its quota).
void fillBlock(const std::vector<uint64_t>& weights, const std::vector<uint8_t>& entered, int shift, uint64_t total,
               uint32_t salt, int bx, int by, uint8_t* cells) {
    std::vector<std::pair<uint32_t, int>> order;
    for (size_t e = 0; e < weights.size(); ++e)
        if (weights[e] > 0) order.push_back({core::hash3(bx, by, salt ^ (0x10u + static_cast<uint32_t>(e))), static_cast<int>(e)});
    std::sort(order.begin(), order.end());
    // A run of an exemplar that has not entered yet shows the entered exemplar before it in the
    // order (after it for the first runs), so every entered exemplar's cells stay one run of the
    // curve (split in two only where the curve wraps).
    std::vector<int> shown(order.size(), -1);
    for (size_t k = 0, last = SIZE_MAX; k < order.size(); ++k) {
        if (entered[order[k].second]) last = k;
        if (last != SIZE_MAX) shown[k] = order[last].second;
    }
    for (size_t k = order.size(); k-- > 0;)
        if (shown[k] < 0) shown[k] = entered[order[k].second] ? order[k].second : shown[k + 1];
    const uint64_t offset = core::hash3(bx, by, salt ^ 0x5u) >> 8;  // in 2^-24 steps
    const uint32_t symmetry = core::hash3(bx, by, salt ^ 0x7u);
    // The runs start at a random step of the curve (wrapping around its end): runs laid from its
    // start split the block on its quadrants (equal exemplars took one 512 px square each, with
    // straight borders repeating every 1024 px).
    const int rotation = static_cast<int>(core::hash3(bx, by, salt ^ 0x8u) % kShareCellsPerBlock);
    size_t k = 0;
    uint64_t run_end = weights[order[0].second] >> shift;
    for (int step = 0; step < kShareCellsPerBlock; ++step) {
        // (step + offset) / kShareCellsPerBlock of the total; below 2^32 * 2^31.
        const uint64_t point = ((static_cast<uint64_t>(step) << 24) | offset) * total / (uint64_t(kShareCellsPerBlock) << 24);
        while (point >= run_end && k + 1 < order.size()) run_end += weights[order[++k].second] >> shift;
        int x = 0, y = 0;
        hilbertCell(kShareCellsPerSide, (step + rotation) % kShareCellsPerBlock, x, y);
        if (symmetry & 1u) x = kShareCellsPerSide - 1 - x;
        if (symmetry & 2u) y = kShareCellsPerSide - 1 - y;
        if (symmetry & 4u) std::swap(x, y);
        cells[y * kShareCellsPerSide + x] = static_cast<uint8_t>(shown[k]);
    }
}

}  // namespace

std::vector<uint8_t> shareCellExemplars(const std::vector<uint64_t>& weights, const std::vector<uint8_t>& entered,
                                        uint32_t salt, int first_bx, int first_by, int blocks_w, int blocks_h) {
    TERRASYNTH_REQUIRE(weights.size() <= 256, "shareCellExemplars: more than 256 exemplars");
    TERRASYNTH_REQUIRE(entered.size() == weights.size(), "shareCellExemplars: one entered flag per exemplar");
    bool any_entered = false;
    for (size_t e = 0; e < weights.size(); ++e) any_entered = any_entered || (entered[e] && weights[e] > 0);
    TERRASYNTH_REQUIRE(any_entered, "shareCellExemplars: no exemplar has entered");
    TERRASYNTH_REQUIRE(blocks_w >= 0 && blocks_h >= 0, "shareCellExemplars: negative block count");
    uint64_t total = 0;
    for (uint64_t w : weights) total += w;
    // Weights scaled by one power of two so their total stays below 2^31 (then the products in
    // fillBlock fit 64 bits); the scaled total is the sum of the scaled weights.
    int shift = 0;
    while ((total >> shift) >= (uint64_t(1) << 31)) ++shift;
    uint64_t scaled_total = 0;
    for (uint64_t w : weights) scaled_total += w >> shift;
    std::vector<uint8_t> cells(static_cast<size_t>(blocks_w) * blocks_h * kShareCellsPerBlock);
    for (int j = 0; j < blocks_h; ++j)
        for (int i = 0; i < blocks_w; ++i)
            fillBlock(weights, entered, shift, scaled_total, salt, first_bx + i, first_by + j,
                      &cells[(static_cast<size_t>(j) * blocks_w + i) * kShareCellsPerBlock]);
    return cells;
}

ShareLayout shareLayout(const ExemplarDatabase& db, const std::vector<int>& entry_levels, int level, int x, int y,
                        int width, int height, uint32_t seed) {
    const int block_side = shareBlockSide(level), share_cell = block_side / kShareCellsPerSide;
    const int first_bx = floorDiv(x, block_side), first_by = floorDiv(y, block_side);
    const int blocks_w = floorDiv(x + width - 1, block_side) + 1 - first_bx;
    const int blocks_h = floorDiv(y + height - 1, block_side) + 1 - first_by;
    std::vector<uint64_t> weights;
    std::vector<uint8_t> entered;
    ShareLayout layout;
    for (size_t e = 0; e < entry_levels.size(); ++e) {
        const AtlasRect& r = db.levels[0].rects[e];
        weights.push_back(entry_levels[e] < 0 ? 0 : static_cast<uint64_t>(r.width) * static_cast<uint64_t>(r.height));
        entered.push_back(entry_levels[e] >= level);
        layout.entering.push_back(entry_levels[e] == level);
    }
    const std::vector<uint8_t> cells =
        shareCellExemplars(weights, entered, shareSalt(seed), first_bx, first_by, blocks_w, blocks_h);
    layout.exemplar.resize(static_cast<size_t>(width) * height);
    for (int ly = 0; ly < height; ++ly)
        for (int lx = 0; lx < width; ++lx) {
            const int gx = x + lx, gy = y + ly;
            const int bx = floorDiv(gx, block_side), by = floorDiv(gy, block_side);
            const int fx = (gx - bx * block_side) / share_cell, fy = (gy - by * block_side) / share_cell;
            const size_t block = static_cast<size_t>(by - first_by) * blocks_w + (bx - first_bx);
            layout.exemplar[static_cast<size_t>(ly) * width + lx] = cells[block * kShareCellsPerBlock + fy * kShareCellsPerSide + fx];
        }
    return layout;
}

ShareLayout entryLayout(const ExemplarDatabase& db, const std::vector<int>& entry_levels, int level,
                        const core::LevelRegion& child, uint32_t seed, const TypePaint* paint) {
    ShareLayout layout = shareLayout(db, entry_levels, level, child.x, child.y, child.width, child.height, seed);
    const std::vector<uint32_t> targets = paint ? constraints::paintedTargetSets(*paint, level, child) : std::vector<uint32_t>();
    if (targets.empty()) return layout;
    // Some exemplar entered at a coarser level (the coarsest holds one): admit_only skips its pixels.
    const auto staying = std::find(layout.entering.begin(), layout.entering.end(), uint8_t{0});
    TERRASYNTH_REQUIRE(staying != layout.entering.end(), "entryLayout: every exemplar enters at this level");
    const auto stay = static_cast<uint8_t>(staying - layout.entering.begin());
    for (size_t i = 0; i < targets.size(); ++i) {
        const uint8_t e = layout.exemplar[i];
        if (targets[i] != 0u && layout.entering[e] && ((targets[i] >> db.exemplar_type[e]) & 1u) == 0u) layout.exemplar[i] = stay;
    }
    return layout;
}

}  // namespace terrasynth::synth
