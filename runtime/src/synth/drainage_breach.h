// Private: drainage by bounded least-cost breaching (Lindsay 2016), one synthesis level at
// a time, after its correction passes (terrasynth/synthesizer.h, Drainage::Breach).
//
// Pixel-based synthesis leaves closed depressions that real fluvial terrain does not have: patches
// placed side by side dam each other's valleys. Every pit of the level (a pixel lower than its 8
// neighbours in (height, global row, global column) order, so flat-bottomed pits count once) looks
// for the cheapest path, within `radius` pixels (Chebyshev) of it, to a pixel at least
// `depth_margin` lower than itself (else to the first strictly lower one it met, else, at coarse
// levels, to the cheapest pixel on the window's edge: DrainageInputs::carve_to_edge, unless copied
// from an exemplar with real basins: DrainageInputs::basin_exemplars); cost = metres
// above the pit plus a millimetre, times the step's length (1 or sqrt 2), summed along the path: a
// cost per cell made diagonal steps 41% cheaper per metre, and coarse channels ran as straight
// 45-degree trenches across valley floors (docs/realism.md). The path is carved to a straight
// profile from the pit down to that pixel by lowering V. Paths are searched on the heights before any carving and combined by taking
// the lowest carve, so the result does not depend on the order of pits; a pixel depends only on
// heights within 2 * radius + 1 of it (the reach the window plan adds to the level's margin).
// The carved heights become the pixels' ceilings (PixelState::ceiling, +inf elsewhere), which the
// next level's correction does not exceed: the channel survives the next level, whose candidates
// re-detail it from the exemplars, and whose own breaching repairs what its detail dams again.
//
// Frozen pixels (s5.3) take their recorded post-breach state and are never carved; pixels under a
// point or curve constraint are never carved either. A path may end at such a pixel, not cross it.
#pragma once

#include <cstdint>
#include <vector>

#include "synth/coherence_fields.h"
#include "synth/reference_kernels.h"

namespace terrasynth::synth {

// The depth below the pit a path should reach (DrainageInputs::depth_margin) as a fraction of the
// level's median 3x3 relief: the finer levels add detail that lowers the floor of a drained basin,
// and a channel that ends barely below the old floor would leave the new one closed again.
constexpr float kBreachDepthFraction = 0.5f;
// kBreachDepthFraction times the median 3x3 relief of the level's exemplar pixels (every other
// row and column), in metres. Cost: a pass over a quarter of the level's atlas.
float breachDepthMargin(const DatabaseLevel& db);

// An exemplar whose own level-0 pixels are at least this share in closed depressions (Priority-Flood
// raises them: DatabaseLevel::closed) has real basins, lava plains or salars, not only valleys: its
// regional lows are kept, not carved to the window's edge (DrainageInputs::basin_exemplars). Level-0
// shares of the shared exemplars: fluvial and glacial 0.4-2.8%, wn_big_butte 5.3%, glac_sthelens_10m
// 6.2%, orom_andes-chile 10.0%, karst and dune fields 11.5-42.4% (docs/realism.md, "Regional lows").
constexpr float kRealBasinShare = 0.04f;

// 1 per exemplar index whose level-0 closed share is at least kRealBasinShare.
std::vector<uint8_t> exemplarsWithRealBasins(const ExemplarDatabase& db);

// breachDepthMargin per level and exemplarsWithRealBasins, computed on first use (a synthesizer owns
// one; not thread-safe).
class DepthMargins {
public:
    float at(const ExemplarDatabase& db, int level);
    const std::vector<uint8_t>& basinExemplars(const ExemplarDatabase& db);

private:
    std::vector<float> margins_;
    std::vector<uint8_t> known_;
    std::vector<uint8_t> basin_exemplars_;
    bool basins_known_ = false;
};

// How far below the pit a path to the window's edge ends at least (DrainageInputs::carve_to_edge), metres.
constexpr float kEdgeDrop = 1.0f;
// A step's cost: (metres above the pit + kBreachStepCost) times its length, 1 or kBreachDiagonal.
constexpr float kBreachStepCost = 1e-3f;
constexpr float kBreachDiagonal = 1.41421356f;
// The carved profile descends from the pit by this share of the drop to the path's end (the lower
// pixel, or the edge drop): cells already below the line stay, so the shallower line leaves more of
// the copied valley floor. With the median offset of the finest levels (kMedianOffsetLevels) full
// depth cut channels that read as trenches at 1:1; three quarters let orom_norway's channels close
// again at 512^2 (docs/realism.md, "Drainage").
constexpr float kBreachProfileDepth = 0.875f;
// The finest level whose breach carves to the window's edge: the regional lows form at the coarse
// levels; levels 2-4 is what was measured (docs/realism.md, "Carving to the window's edge").
constexpr int kBreachToEdgeFromLevel = 2;

struct DrainageInputs {
    const std::vector<uint8_t>* coherence = nullptr;  // W codes per region pixel; empty: none frozen
    const PassHistory* drained = nullptr;             // previous synthesis after breaching; may be empty
    const std::vector<float>* blend = nullptr;        // constraint sums, 4 per region pixel; may be empty
    float depth_margin = 0.0f;                         // breachDepthMargin of the level, metres
    // A pit with no lower pixel within the radius is carved to the cheapest pixel on its search
    // window's edge, which is lowered below the pit (by kBreachProfileDepth times depth_margin or
    // kEdgeDrop, the larger), so the channel leads out of the basin and the next level's breach
    // may continue it. Such pits are the regional lows of the initial patches (valleys ending
    // against higher patches) and the large basins left at 1024^2; synthesis_driver.cpp sets it
    // from level kBreachToEdgeFromLevel up.
    bool carve_to_edge = false;
    // The pixels whose result matters (global, at the level): what the next finer level or the
    // output reads. Only pits within `radius` of it can carve it, so the others are not searched.
    // Empty: the whole region.
    LevelRegion needed;
    // Per exemplar index (exemplarsWithRealBasins): 1 keeps the regional lows copied from that
    // exemplar instead of carving them to the edge. Null or short: none kept.
    const std::vector<uint8_t>* basin_exemplars = nullptr;
    // The level's levelGroundFlags and their tolerance (synth/level_ground.h):
    // where the pit is copied from level ground, the path's cells copied from the same level ground
    // (a level source at most level_tolerance from the pit's source height) and at most
    // level_tolerance above the pit are not carved, so a path leaves a lake or a flat floor level
    // and cuts only its rim (carving them drew a trench across it). Null: every path cell is carved.
    const std::vector<uint8_t>* level_ground = nullptr;
    float level_tolerance = 0.0f;
};

struct BreachCounts {
    size_t pits = 0;      // pits found in the region
    size_t breached = 0;  // of them, drained by a carved path
};

// Per-pixel buffers of breachPits, kept between calls by a synthesizer that breaches often: at
// level 0 of a 1024^2 synthesis they are about 11 MB, and first touching fresh memory costs several
// times a pass over touched memory (the OpenCL backend's 17 MB staging copy: 8.9 ms against 1.7).
// Not thread-safe: one per synthesizer, like DepthMargins.
struct BreachScratch {
    std::vector<uint8_t> fixed;
    std::vector<float> z, row_min;
};

// Breaches the region's pits (see above), lowering V along carved paths and setting every pixel's
// ceiling. The reference backend's breach, and the reference of the OpenCL backend's
// (cl/cl_drainage.h, kernels/drainage.cl), which repeats it bit for bit on the device. Pits are
// searched on up to 8 threads (hardware concurrency); paths combine by the lowest carve (a carve
// of -0 counts as +0), so the result does not depend on the thread count. A search that cannot reach `depth_margin` below its
// pit (the window's lowest height says so) stops at the first lower pixel, and one with nothing
// lower in reach (carve_to_edge) at the first edge cell it settles: where an exhausted search would
// have ended. Pixels outside `inputs.needed` grown by `radius` may miss carves from
// pits beyond it.
// scratch: optional; nullptr uses buffers of the call's own.
// state: the region's region.pixels() pixels, row-major (the OpenCL backend passes its mapped buffer).
BreachCounts breachPits(const DatabaseLevel& db, const LevelRegion& region, int radius, const DrainageInputs& inputs,
                        PixelState* state, BreachScratch* scratch = nullptr);

}  // namespace terrasynth::synth
