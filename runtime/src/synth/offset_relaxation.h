// Private: relaxation of the offsets V after a level's correction passes (terrasynth/synthesizer.h,
// SynthesisParams::relax_offsets).
//
// Why: the paper's synthesis (Gain et al. 2015 s3) copies each pixel's height as E(S) + V, with the
// offset V interpolated by the upsampling (eq. 1-2) and kept by the correction, which only chooses S.
// Inside a patch V is therefore smooth (close to harmonic) and tilts whatever the patch copies: on
// flat sources (valley floors, lakes, fjord floors, dune streets) it adds 2-3.5 degrees of slope that
// the exemplar does not have, and where two patches meet, the step between their sources' heights
// stays as a seam of pits and mottle. The relaxation re-chooses V, S fixed, so that each pixel's
// height differences to its 8 neighbours are the exemplar's own differences at their sources:
//
//   minimise  sum over neighbour pairs (p, q) of  w_pq (h_q - h_p - t_pq)^2  +  eps sum_p (V_p - V0_p)^2
//
// with h = E(S) + V, t_pq the mean of the exemplar's step from S_p towards q and from S_q back
// towards p (both sources agree on it inside a patch, where S_q = S_p + (q - p) and t is exactly
// E(S_q) - E(S_p), so patches' interiors keep their heights), and V0 the offsets before relaxing.
// The weight w_pq = sigma^2 / (t^2 + sigma^2), sigma = tan(kRelaxFlatSlopeDegrees) times the step's
// length in metres, is 1 on gentle steps and falls on steep ones (halved again for diagonal pairs):
// flats are made flat across seams, cliffs and ridges keep their own heights. Solved by weighted
// Jacobi iterations (each pixel moves to the weighted mean its neighbours ask of it), which need no
// ordering: every iteration reads the previous one only, so a pixel after k iterations depends on
// the state within k pixels (Chebyshev), the reach the window plan adds to the level's margin
// (relaxationIterations), and windows stay bit-identical to larger windows.
//
// Fixed (never moved, but still asked by their neighbours): pixels under a point or curve constraint
// (blend > 0), pixels carrying a drainage ceiling from the level above (moving them would undo or
// overshoot the breach's channel; left free they made staircases against the clamp), and frozen
// pixels (s5.3), which take their recorded relaxed state first.
#pragma once

#include <cstdint>
#include <vector>

#include "synth/coherence_fields.h"
#include "synth/reference_kernels.h"

namespace terrasynth::synth {

// A step is "gentle" (full weight) up to this slope: exemplar steps much steeper than it keep their
// heights instead of being averaged with their neighbours' (docs/realism.md, "Offset relaxation").
constexpr float kRelaxFlatSlopeDegrees = 5.0f;
// eps of the energy above: how strongly V is held to its value before the relaxation, against a
// neighbour pair's weight of at most 1. Small, so gentle seams close; non-zero, so an isolated
// pixel keeps its height.
constexpr float kRelaxOffsetStiffness = 0.001f;

// Jacobi iterations at `level` when relaxation is on: 4 at level 0 (its detail is the exemplars'
// own finest octave, and each iteration widens level 0's margin by a pixel), 8 above (16 were no
// better, at twice the margins: docs/realism.md). Also the
// reach in pixels of that level that synthesis_driver.cpp adds to the level's margin.
int relaxationIterations(int level);

struct RelaxationInputs {
    const std::vector<uint8_t>* coherence = nullptr;  // W codes per region pixel; empty: none frozen
    const PassHistory* relaxed = nullptr;             // previous synthesis after relaxing; may be empty
    const std::vector<float>* blend = nullptr;        // constraint sums, 4 per region pixel; may be empty
};

// Relaxes V of the `region` pixels of `state` (row-major, region.pixels() entries) at a level with
// `spacing_m` metres per pixel; S and the ceilings are not changed. Deterministic for any thread
// count (rows are split among workers, every iteration reads only the previous one).
void relaxOffsets(const DatabaseLevel& db, const LevelRegion& region, double spacing_m, int iterations,
                  const RelaxationInputs& inputs, PixelState* state);

}  // namespace terrasynth::synth
