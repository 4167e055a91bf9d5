// Private: where synthesis starts. The coarsest synthesized level is the coarsest one at
// which most of the database is still large enough to synthesize from, and it starts from
// irregular patches of exemplar coordinates rather than from independent random coordinates.
//
// Why: on an exemplar of a few pixels (648 px at level 6 is 10x10), and from per-pixel random
// coordinates, every neighbourhood is inconsistent, and eq. 7 (a squared distance to the average of
// the neighbourhood) is smallest for the flattest candidates. Flat coordinates only have flat
// k-coherence candidates (eq. 3), so the choice is never undone at the finer levels: one-exemplar
// syntheses of mixed exemplars drew 100% of their pixels from the flattest 30% of the exemplar.
// Started from coherent patches on a level where the exemplar is at least kMinCoarsestSide
// pixels, the finer levels keep the exemplar's mix (docs/realism.md has the figures).
#pragma once

#include <cstdint>
#include <vector>

#include "core/level_region.h"
#include "terrasynth/database.h"
#include "terrasynth/status.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::synth {

// Correction passes added at the coarsest synthesized level. Starting from a level where the
// exemplars are large, the first level holds whole exemplar slopes; point and curve constraints
// pull halfway per pass (eq. 8-9) and now act on fewer levels than when synthesis started at the
// database's coarsest level, so the broad slope they ask for needs more pulls there. The level
// holds about 1/256 of the output's pixels: the cost is negligible.
constexpr int kCoarsestLevelExtraPasses = 2;

// The coarsest level at which exemplars holding at least half of the database's level-0 pixels are
// still kMinCoarsestSide pixels on their shorter side (0 when none is).
int automaticCoarsestLevel(const ExemplarDatabase& db);

// Share blocks: which exemplar each pixel starts from. The world grid is cut into blocks of
// kShareBlockSide0 level-0 pixels (a 1024^2 synthesis at the origin is one block), each into
// kShareCellsPerSide^2 share cells. Along a Hilbert curve over a block's cells (one of its eight
// symmetries per block, entered at a random step and wrapping around its end), the exemplars take
// consecutive runs, in a random order per block, of lengths proportional to their level-0 area
// (systematic sampling at one random offset per block: each gets the floor or the ceiling of its
// quota). So every block holds every exemplar in proportion to its area, each as one compact region
// (two for the run that wraps), whatever the seed. The layout is the same at every level (in
// level-0 terms).
//
// An exemplar enters at the coarsest synthesized level if it is kMinCoarsestSide pixels on its
// shorter side there; a smaller one enters at the coarsest level where it is kLateEntrySide pixels
// (entryLevels). Until then its cells are its predecessor's along the curve; at its level,
// upsampling replaces them by patches of it that keep the coarser levels' mean heights (V takes
// the mode-0 gap; drainage ceilings kept), so it brings its detail onto the terrain around it.
// Why so late: from a level where it is a few pixels, an exemplar has no structure to copy (its
// candidates lie in its margin), and the correction passes of every later level move its region's
// border; a small region loses more than it gains. The five 10-30 m exemplars of the shared set
// (13-24 px at level 4 of a 92.6 m database) kept, of their share of a 17-exemplar synthesis over
// six seeds: entering at 40 px 0.21-1.64x (15 of 30 runs outside 0.5-2x), at 80 px 0.33-1.69x
// (3 of 30), at 160 px 0.47-1.91x (1 of 30); all at level 4, seeds 1-3, 0.09-2.91x (5 of 15)
// (docs/realism.md, "Share blocks").
// The price: such an exemplar gives its region the detail below a few hundred pixels of its own
// size, not its broadest forms.
//
// Why share blocks: the exemplar used to be drawn per initial patch (by systematic sampling over
// 3x3 cells), and a 1024^2 synthesis holds about nine patches: at most nine exemplars of a
// 17-exemplar database appeared, and one of under 2% of the database was absent or five times over
// its share whenever drawn (docs/realism.md, "Share blocks"). A patch's copy offset still comes from
// its patch cell; the share cells only say from which exemplar.
constexpr int kShareBlockSide0 = 1024;
constexpr int kShareCellsPerSide = 16;
constexpr int kShareCellsPerBlock = kShareCellsPerSide * kShareCellsPerSide;
constexpr int kLateEntrySide = 4 * kMinCoarsestSide;

// The side of a share block in pixels of `level` (>= 0): kShareBlockSide0 >> level, at least
// kShareCellsPerSide (one pixel per share cell).
int shareBlockSide(int level);

// Per exemplar, the level it enters a synthesis whose coarsest level is `coarsest`: `coarsest` if
// it is kMinCoarsestSide pixels on its shorter side there, else the coarsest level where it is
// kLateEntrySide pixels (0 if none); when no exemplar is kMinCoarsestSide at `coarsest`, each enters
// where it first has interior pixels. -1 for an exemplar without interior pixels at the level it
// would enter (never used).
std::vector<int> entryLevels(const ExemplarDatabase& db, int coarsest);

// entryLevels for a synthesis starting at `coarsest`, or an error naming the level when no
// exemplar has interior pixels to start from there.
Result<std::vector<int>> startingEntryLevels(const ExemplarDatabase& db, int coarsest);

// Whether some exemplar of `entry_levels` enters at `level`.
bool entersAt(const std::vector<int>& entry_levels, int level);

// The exemplar of every share cell of the blocks [first_bx, first_bx + blocks_w) x [first_by,
// first_by + blocks_h), block by block in row order, each block's kShareCellsPerBlock cells in row
// order, at a level where exemplar e has entered iff entered[e]. `weights`: per exemplar, its
// level-0 pixel count (0: never used; at most 256 exemplars); at least one with a weight has
// entered. `salt`: shareSalt.
// Pure function of its arguments (windowed determinism).
std::vector<uint8_t> shareCellExemplars(const std::vector<uint64_t>& weights, const std::vector<uint8_t>& entered,
                                        uint32_t salt, int first_bx, int first_by, int blocks_w, int blocks_h);

// The share layout's salt: one per seed, the same at every level.
uint32_t shareSalt(uint32_t seed);

// The share layout of one region of one level: per region pixel (row-major) the exemplar of its
// share cell, and per exemplar whether it enters at this level. `entry_levels` from entryLevels,
// with at least one exemplar entered at `level`. (Looking the cells up at positions warped by
// smooth noise, for less regular borders, changed the small regions' areas: of the five 10-30 m
// exemplars, 3 of 30 runs fell outside a factor 2 with a warp of one cell, 6 with two, against 1
// without; the straight stretches of valley along some borders stayed.)
struct ShareLayout {
    std::vector<uint8_t> exemplar;
    std::vector<uint8_t> entering;
};
ShareLayout shareLayout(const ExemplarDatabase& db, const std::vector<int>& entry_levels, int level, int x, int y,
                        int width, int height, uint32_t seed);

// The share layout of `child` at `level`, where exemplars enter, for its upsampling (admit_only):
// shareLayout, except that a painted pixel whose target set (s5.2, R^i of the `paint`) excludes the
// type of its share cell's entering exemplar does not admit it (it shows a non-entering exemplar)
// and keeps the coordinate the coarser levels chose. Why: the coarser levels' type rejection put a
// painted type there, and an entry at one of the finest two levels, where the paper disables type
// constraints (s5.2, last paragraph), has no pass to reject it again: a 10-30 m exemplar's cells
// inside a region painted over the middle quarter of a 1024^2 17-exemplar synthesis left 89-94% of
// it of the painted type. `paint` null or empty: shareLayout.
ShareLayout entryLayout(const ExemplarDatabase& db, const std::vector<int>& entry_levels, int level,
                        const core::LevelRegion& child, uint32_t seed, const TypePaint* paint);

// At the coarsest level a candidate from another exemplar than the pixel's share cell costs this
// many times its eq. 7 cost (the factor s4 gives C_2). Why: the exemplars start from their exact
// share of a block, but that level's correction passes (16 subpasses and more, over regions of
// about 17 px) moved the borders until a region was eaten: of the 17 shared exemplars, orom_alaska
// kept 2.5% of its 6.9% after level 4 (seed 2), and its share did not change after that level. The
// finer levels move borders freely. Over seeds 1-6, the twelve large exemplars: 0.37-1.65x of
// their share without it (3 of 72 runs outside 0.5-2x), 0.66-1.29x with 2 (none), 0.77-1.30x with 4.
constexpr float kLayoutWeight = 2.0f;

}  // namespace terrasynth::synth
