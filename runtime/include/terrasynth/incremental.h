// terrasynth/incremental.h: interactive editing of one terrain extent (Gain et al. 2015 s5.3).
//
// Keeps the heights and the synthesis history (every level and pass) of an extent. An edit of the
// constraints names the level-0 rectangle it can affect (for a point constraint: the union of its
// old and new area of effect); only that rectangle, a coherent band around it and the synthesis
// margins are re-synthesized. Inside the rectangle the weights are Free, in the band Coherent, and
// beyond the band Frozen, so the result equals a full re-synthesis with those weights, and pixels
// beyond the band keep their heights bit for bit.
//
// Not thread-safe (one editor thread). Uses the caller's Synthesizer, which must outlive it.
#pragma once

#include <memory>

#include "terrasynth/synthesizer.h"

namespace terrasynth {

class IncrementalTerrain {
public:
    // Synthesizes the whole extent once, recording its history.
    static Result<IncrementalTerrain> create(Synthesizer& synthesizer, const PixelWindow& extent, SynthesisParams params);

    const Heightfield& heights() const { return heights_; }
    const SynthesisParams& params() const { return params_; }
    // Pixels of the coherent band kept around an edit's rectangle (level-0 pixels).
    static constexpr int kCoherentBand = 32;

    // Applies new constraints. `changed` is the level-0 rectangle (global pixels) the change can
    // affect. Re-synthesizes the affected part and merges it into heights() and the history.
    Status update(std::shared_ptr<const SynthesisConstraints> constraints, const PixelWindow& changed);
    // Pixels re-synthesized by the last update (output window only), for benchmarks.
    PixelWindow lastWindow() const { return last_window_; }

private:
    IncrementalTerrain(Synthesizer& s, PixelWindow extent, SynthesisParams params)
        : synthesizer_(&s), extent_(extent), params_(std::move(params)) {}
    Synthesizer* synthesizer_;
    PixelWindow extent_;
    SynthesisParams params_;
    Heightfield heights_;
    std::shared_ptr<SynthesisHistory> history_;
    PixelWindow last_window_;
};

}  // namespace terrasynth
