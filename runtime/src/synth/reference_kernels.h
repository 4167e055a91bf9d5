// Private: the plain C++ reference of every synthesis kernel (kernels/synthesis.cl), step for step
// and with the same float arithmetic, so the OpenCL path can be checked against it
// (SynthesisDifferential in tests/cl_synthesis_test.cpp) and so the algorithm can be read without OpenCL.
#pragma once

#include <vector>

#include "constraints/constraint_fields.h"
#include "synth/coherence_fields.h"
#include "synth/initial_patches.h"
#include "synth/synthesis_plan.h"
#include "synth/type_seeds.h"
#include "terrasynth/database.h"

namespace terrasynth::synth {

// C_1 of a candidate source outside its exemplar's interior: none. Moving it to the nearest
// interior pixel (as before) repeated the interior's edge row or column wherever a coherent patch
// ran into it, a fixed point of the passes that showed as stripes on exemplars barely taller than a
// patch (docs/realism.md, ttb_bigtujunga); without it the pixel takes another neighbour's
// candidate or C_2, a seam the passes repair.
constexpr uint32_t kNoIdentityCandidate = 0xffffffffu;

// C_1(c) (s4, Lefebvre & Hoppe 2005's identity candidate) of atlas pixel c: c itself when it lies
// in its exemplar's interior and off its NoData voids (type not kNoType), or in no exemplar, else
// kNoIdentityCandidate. The OpenCL backend
// bakes it into its candidate table; the reference calls it per candidate.
uint32_t identityCandidate(const DatabaseLevel& db, uint32_t c);

// Per synthesis pixel: exemplar atlas coordinate S (x, y), height offset V, and the drainage ceiling
// (synth/drainage_breach.h): the height a channel carved at the coarser level must not
// rise above; +infinity where there is none.
struct PixelState {
    float x = 0, y = 0, v = 0, ceiling = 0;
};

// A frozen (or kept) pixel takes its previous result `previous` at region pixel `pixel`:
// coordinate and offset V; its ceiling is unchanged.
void takePrevious(const DatabaseLevel& db, const PassHistory& previous, size_t pixel, PixelState& out);

// The pixels a step after the correction passes (offset relaxation, drainage) leaves as they are,
// 1 per region pixel in `fixed`: frozen ones (s5.3), which first take `recorded` (the previous
// synthesis's state after that step) where it has them, and those under a point or curve
// constraint (blend > 0). Any input may be null or of the wrong size (none of that kind).
void holdFrozenAndConstrained(const DatabaseLevel& db, const std::vector<uint8_t>* coherence, const PassHistory* recorded,
                              const std::vector<float>* blend, size_t pixels, PixelState* state,
                              std::vector<uint8_t>& fixed);

// Irregular patches of exemplar coordinates, each pixel from its share cell's exemplar
// (synth/initial_patches.h): at the coarsest level every pixel (V = 0, no drainage ceiling); with
// admit_only, at a finer level, the pixels of the exemplars entering there (V and ceiling kept).
void referencePatches(const DatabaseLevel& db, const ShareLayout& layout, const LevelRegion& region, uint32_t seed,
                      int level, bool admit_only, std::vector<PixelState>& state);

// Eq. 1-2: every parent pixel initialises its 2x2 children, jittered by r*H(p).
void referenceUpsample(const DatabaseLevel& parent_db, const DatabaseLevel& child_db, const LevelRegion& parent_region,
                       const std::vector<PixelState>& parent, const LevelRegion& child_region, float jitter,
                       uint32_t seed, int child_level, std::vector<PixelState>& child);

// The finest levels (0 .. kMedianOffsetLevels - 1) take eq. 7's best offset h as the median of the
// four diagonal mode-0 gaps, not their mean (the least-squares h of Gain et al. s3): where a pixel's
// diagonals come from two patches, the mean sets the height between them and the seam shows as a
// mottle of half-steps at 1:1; the median follows the three that agree. Coarser levels keep the
// mean (at every level the median let more closed depressions through the drainage breach,
// docs/realism.md, "Median offset").
constexpr int kMedianOffsetLevels = 2;

// What a correction subpass needs besides the state: the level, its constraints and seed lists.
struct CorrectionContext {
    int level = 0;
    float meters_per_pixel0 = 1.0f;
    uint32_t seed_salt = 0;
    constraints::LevelConstraints constraints;
    SeedTable seeds;
    std::vector<uint8_t> coherence;  // W^i codes per region pixel (empty: no previous result)
    PassHistory previous;            // the previous result of the current pass (s5.3)
    std::vector<uint8_t> layout;     // the coarsest level's shareLayout exemplars per region pixel (else empty)
    // The level's levelGroundFlags per atlas pixel and their tolerance (synth/level_ground.h); null:
    // no level ground.
    const std::vector<uint8_t>* level_ground = nullptr;
    float level_tolerance = 0.0f;
    // lowestExemplarHeight of the level (synth/level_ground.h): the floor of unconstrained heights.
    float lowest_height = -INFINITY;
};

// Eq. 3-7 (and the constraints of s5.1-5.2) for the pixels of one parity class, in place.
// Only pixels at least `inset` pixels inside the region are corrected.
void referenceCorrect(const DatabaseLevel& db, const LevelRegion& region, int parity_x, int parity_y, int inset,
                      const CorrectionContext& context, std::vector<PixelState>& state);

// A drag preview's level (SynthesisParams::preview_levels), on the upsampled state: every pixel
// that is not Free and has a previous result takes that result, as a Frozen pixel of `correct`
// does; the others keep their coordinate, snapped to the nearest whole atlas pixel so that the
// history recorded from it gives back the same heights, with V interpolated bilinearly between the
// parents (upsampling copies a parent's V to its 2x2 children, which only the correction passes
// would smooth: a constraint's ramp would show as 2-pixel steps). `coherence` and `previous` are per
// region pixel (empty: none kept). `state`: region.pixels() states, row-major (the OpenCL backend
// passes its mapped buffer).
void referencePreviewLevel(const DatabaseLevel& db, const LevelRegion& region, const std::vector<uint8_t>& coherence,
                           const PassHistory& previous, PixelState* state);

// E at a real-valued atlas coordinate (bilinear), in metres: the height resolve gives a pixel whose
// state is (sx, sy) before its offset V.
float heightBilinear(const DatabaseLevel& db, float sx, float sy);

// E(S) + V of a pixel, in metres: heightBilinear plus the offset, read straight from the level at
// whole-pixel coordinates (corrected pixels have them; the same value). Inline because a call per
// pixel cost more than the rest of the drainage breach's height pass.
inline float pixelHeight(const DatabaseLevel& db, const PixelState& s) {
    const int ix = static_cast<int>(s.x), iy = static_cast<int>(s.y);  // atlas coordinates are >= 0
    if (static_cast<float>(ix) == s.x && static_cast<float>(iy) == s.y)
        return db.height_m[static_cast<size_t>(iy) * db.width + ix] + s.v;
    return heightBilinear(db, s.x, s.y) + s.v;
}

// Final heights E(S) + V (bilinear in E) of `out` (inside `region`), and optionally the sources.
void referenceResolve(const DatabaseLevel& db, const LevelRegion& region, const std::vector<PixelState>& state,
                      const LevelRegion& out, float* heights, float* source_x, float* source_y,
                      uint8_t* source_exemplar);

}  // namespace terrasynth::synth
