// Private: which part of every pyramid level must be synthesized for an output window.
//
// Correction reads neighbours up to 2 pixels away (eq. 3-6), so each subpass spoils a 2-pixel ring
// at the border of what was computed; upsampling reads the parent pixel floor(p/2). Working from the
// output window up to the coarsest level, each level's region is its children's parents plus
// 2 * 4 * passes pixels (plus the drainage step's reach, when it runs). Everything is addressed in global pixel coordinates and all randomness is a
// hash of global coordinates, so the output window is exactly what a larger computation would give.
#pragma once

#include <cstdint>
#include <vector>

#include "core/level_region.h"
#include "terrasynth/limits.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::synth {

using core::LevelRegion;  // what a plan is made of (core/level_region.h)

struct SynthesisPlan {
    int output_level = 0;
    int coarsest_level = 0;
    int passes = 2;
    std::vector<LevelRegion> regions;  // indexed by level; valid for output_level..coarsest_level
    // What each level must produce: the output at output_level, the parents of the finer level's
    // region above it; regions[level] is this grown by the level's margin.
    std::vector<LevelRegion> needed;
    LevelRegion output;                // the requested window at output_level
};

// Reach of one correction subpass in pixels (eq. 6 reads S at p + (2*dx, dy)).
constexpr int kSubpassReach = 2;
// Subpass parities in order (Lefebvre & Hoppe 2005 use 2x2 subpasses).
constexpr int kSubpassParity[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
// Global coordinates must stay well inside int32 at every level.
constexpr int64_t kMaxGlobalCoordinate = limits::kMaxWindowOrigin;

// extra_margin[level] (optional): pixels a step after the level's correction reads beyond what it
// must produce (drainage); added to that level's margin.
SynthesisPlan planSynthesis(const PixelWindow& window, int output_level, int coarsest_level, int passes,
                            const std::vector<int>& extra_margin = {});

// Floor division for negative global coordinates.
inline int floorDiv2(int v) { return v >> 1; }  // arithmetic shift = floor for two's complement
inline int floorDiv(int v, int d) { return v >= 0 ? v / d : -((d - 1 - v) / d); }  // d > 0

}  // namespace terrasynth::synth
