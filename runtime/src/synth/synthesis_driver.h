// Private: the level loop of pyramid synthesis (paper s4), shared by the reference and OpenCL
// backends, which only differ in how they execute each step.
#pragma once

#include "constraints/constraint_fields.h"
#include "synth/coherence_fields.h"
#include "synth/drainage_breach.h"
#include "synth/offset_relaxation.h"
#include "synth/synthesis_plan.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::synth {

// Correction passes of `level` when `coarsest` is the coarsest synthesized level: the coarsest one
// gets kCoarsestLevelExtraPasses more (initial_patches.h).
int passesAt(const SynthesisParams& params, int level, int coarsest);
// Passes a SynthesisHistory records at `level`: the correction passes, plus the relaxed state when
// offsets are relaxed, plus the drained state when drainage is on (synthesizer.h).
int historyPassesAt(const SynthesisParams& params, int level, int coarsest);
// Pixels each level reads beyond the plan's uniform correction margin: the coarsest level's extra
// passes, the offset relaxation's reach (offset_relaxation.h) and the drainage step's reach
// (drainage_breach.h); planSynthesis's extra_margin.
std::vector<int> extraMargins(const SynthesisParams& params, int coarsest);
// The finest levels (0 .. kUnjitteredLevels - 1) are upsampled without eq. 1's jitter, whatever
// SynthesisParams::jitter says: a child starts at its parent's coordinate, 2x + (0 or 1), so the
// runs of coordinates the coarser levels settled reach the output as runs, and the correction
// passes change only what does not fit. Lefebvre & Hoppe 2005, whose jitter step Gain et al.
// follow, set its amount per level. Jittered at levels 0-1 too, close-ups were told apart from
// the exemplar a little more often (docs/realism.md, "Unjittered finest levels").
constexpr int kUnjitteredLevels = 2;
// Most passes any level records (4 correction passes + the extra ones + relaxation + drainage).
constexpr int kMaxHistoryPassesPerLevel = 8;

class SynthesisSteps {
public:
    virtual ~SynthesisSteps() = default;
    virtual Status init(int level, const LevelRegion& region, uint32_t seed) = 0;
    // Upsample + jitter from level+1 (the previous step's state) into `child` at `level`, where
    // exemplars may enter (entryLayout with `paint`, null when nothing is painted).
    virtual Status upsample(int level, const LevelRegion& parent, const LevelRegion& child, float jitter,
                            uint32_t seed, const TypePaint* paint) = 0;
    // Called once per level before its correction subpasses. `coherence` holds the W^i codes per
    // region pixel, empty when there is no previous synthesis to be coherent with.
    virtual Status beginLevel(int level, const LevelRegion& region, const constraints::LevelConstraints& constraints,
                              const std::vector<uint8_t>& coherence, uint32_t seed) = 0;
    // Called before the 4 subpasses of each pass with the previous result of that pass (s5.3).
    virtual Status beginPass(int level, const LevelRegion& region, const PassHistory& previous) = 0;
    // Copies the state after a pass into `out` (index and V per region pixel).
    virtual Status recordPass(int level, const LevelRegion& region, SynthesisHistory::Pass& out) = 0;
    // A drag preview's level instead of its passes (SynthesisParams::preview_levels): pixels that are
    // not Free take `previous` (the level's last recorded pass), the others keep the upsampled state
    // snapped to whole atlas pixels (referencePreviewLevel).
    virtual Status previewLevel(int level, const LevelRegion& region, const std::vector<uint8_t>& coherence,
                                const PassHistory& previous) = 0;
    // Corrects the pixels of one parity class at least `inset` pixels inside the region: the ring
    // outside would be spoiled by the margin anyway (synthesis_plan.h), so it is not computed.
    virtual Status correct(int level, const LevelRegion& region, int parity_x, int parity_y, int inset) = 0;
    // Offset relaxation (offset_relaxation.h) after the correction passes, before drainage.
    virtual Status relax(int level, const LevelRegion& region, int iterations, const RelaxationInputs& inputs) = 0;
    // Drainage (drainage_breach.h): breaches the level's pits after its correction passes.
    virtual Status drain(int level, const LevelRegion& region, int radius, const DrainageInputs& inputs) = 0;
    // breachDepthMargin of a level, cached by the backend.
    virtual float depthMargin(int level) = 0;
    // exemplarsWithRealBasins of the database, cached by the backend.
    virtual const std::vector<uint8_t>& basinExemplars() = 0;
    // levelGroundFlags of a level (level_ground.h), cached by the backend.
    virtual const std::vector<uint8_t>& levelGround(int level) = 0;
    virtual Status resolve(int level, const LevelRegion& region, const LevelRegion& out, SynthesisOutput& output,
                           bool want_sources) = 0;
};

// Validates the request and runs init -> (correct, upsample)* -> correct -> resolve, asking
// `stop_requested` (may be null; SynthesizerOptions::stop_requested) before each level.
Result<SynthesisOutput> runSynthesis(const ExemplarDatabase& db, const PixelWindow& window,
                                     const SynthesisParams& params, int output_level, bool want_sources,
                                     SynthesisSteps& steps, const std::function<bool()>& stop_requested,
                                     size_t* peak_state_pixels = nullptr);

// Checks parameters and window against the database; the message names the parameter.
Status validateRequest(const ExemplarDatabase& db, const PixelWindow& window, const SynthesisParams& params,
                       int output_level);
int coarsestLevel(const ExemplarDatabase& db, const SynthesisParams& params);

}  // namespace terrasynth::synth
