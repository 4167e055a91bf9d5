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
#include <vector>

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
    // Point constraints whose site lies in `changed` are lifted first (liftPointConstraints, with
    // this update's coherence) so their sites land on their heights; see holdPointHeights.
    Status update(std::shared_ptr<const SynthesisConstraints> constraints, const PixelWindow& changed);
    // What an edit from the current constraints to `next` manipulates (s5.3: W = 1 inside the
    // manipulated constraints' reach): the discs of points and the reach bands of curves that are in
    // one set and not the other (a changed lift counts), and the pixels whose painted type changed.
    // `mask` is per extent pixel (1 = Free), `box` its bounding box (width 0 = nothing changed).
    struct EditArea {
        PixelWindow box;
        std::vector<uint8_t> mask;
    };
    EditArea areaAffectedBy(const SynthesisConstraints* next) const;
    // update() for exactly areaAffectedBy(next): Free where its mask is set, Coherent in a band
    // around its box. `changed` (optional) receives the box.
    Status applyEdit(std::shared_ptr<const SynthesisConstraints> next, PixelWindow* changed = nullptr);
    // Copy-paste (s5.3, fig. 8): the polygon `source` (level-0 pixels of the terrain's global grid,
    // or of exemplar `exemplar` when >= 0) is moved by (dx, dy) pixels and raised by
    // `height_offset_m`. The pasted coordinates are written for every level and pass and frozen, and
    // a Free band of kCoherentBand pixels around the target lets the surroundings blend in.
    using Paste = PasteConstraint;
    Status paste(const Paste& paste);
    // Freeze brush: marks level-0 pixels (global grid, mask value != 0 and != TypePaint::kUnpainted)
    // frozen for every later update and paste.
    void freeze(const TypePaint& mask);
    // Level-0 pixels frozen so far by pastes (and kept frozen by later updates).
    const std::vector<uint8_t>& frozenMask() const { return frozen_; }

    // Whether update() lifts point constraints (default true); false = the paper's plain targets.
    void holdPointHeights(bool hold) { hold_point_heights_ = hold; }

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
    std::vector<uint8_t> frozen_;  // per extent pixel, 1 = frozen (pasted)
    bool hold_point_heights_ = true;
    Status resynthesize(const PixelWindow& free_area, const std::vector<uint8_t>* free_mask,
                        std::shared_ptr<const SynthesisConstraints> constraints, bool lift_points);
};

}  // namespace terrasynth
