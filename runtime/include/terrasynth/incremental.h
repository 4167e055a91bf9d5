// terrasynth/incremental.h: interactive editing of one terrain extent (Gain et al. 2015 s5.3).
//
// Keeps the heights and the synthesis history (every level and pass) of an extent. An edit of the
// constraints names the level-0 rectangle it can affect (for a point constraint: the union of its
// old and new area of effect); only that rectangle, a coherent band around it and the synthesis
// margins are re-synthesized. Inside the rectangle the weights are Free, in the band Coherent, and
// beyond the band Frozen, so the result equals a full re-synthesis with those weights, and pixels
// beyond the band keep their heights bit for bit.
//
// Undo: the heights, the history and the frozen mask are edited in place; between beginJournal()
// and takeJournal() every change is recorded by tile (what an edit touched, once), and
// swapJournal() puts the recorded state back (and keeps the replaced one, so the same call redoes).
//
// Not thread-safe (one editor thread). Uses the caller's Synthesizer, which must outlive it.
#pragma once

#include <memory>
#include <vector>

#include "terrasynth/synthesizer.h"

namespace terrasynth {

namespace detail {
class TileJournal;
}

// The level-0 pixels of `extent` (row-major, 1 = frozen) that a paste freezes: those whose centres
// lie inside its target polygon, at least IncrementalTerrain::kPasteBlendPx from its edge.
std::vector<uint8_t> pasteTargetMask(const PasteConstraint& paste, const PixelWindow& extent);

class IncrementalTerrain {
public:
    // Synthesizes the whole extent once, recording its history.
    static Result<IncrementalTerrain> create(Synthesizer& synthesizer, const PixelWindow& extent, SynthesisParams params);
    IncrementalTerrain(IncrementalTerrain&&) noexcept;
    IncrementalTerrain& operator=(IncrementalTerrain&&) noexcept;
    ~IncrementalTerrain();

    const Heightfield& heights() const { return heights_; }
    const SynthesisParams& params() const { return params_; }
    // Pixels of the coherent band kept around an edit's rectangle (level-0 pixels).
    static constexpr int kCoherentBand = 32;
    // A paste's rim: its pixels closer than this to the target polygon's edge are written but not
    // frozen, and re-synthesized Free with the band around the paste, so the paste and its
    // surroundings meet without a step (measured: docs/project-format.md, `constraints.pastes`).
    static constexpr int kPasteBlendPx = 6;

    // Applies new constraints. `changed` is the level-0 rectangle (global pixels) the change can
    // affect. Re-synthesizes the affected part and merges it into heights() and the history.
    // Point constraints whose site lies in `changed` are lifted first (liftPointConstraints, with
    // this update's coherence) so their sites land on their heights, then the stations of curve
    // lift profiles that lie in `changed` (liftCurveConstraints); see holdPointHeights. A curve
    // given without a lift profile takes the current one of a curve with the same course, so an
    // unchanged curve keeps its lift and an edited one starts its search from it.
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
    // `height_offset_m`. The pasted coordinates are written for every pass of level 0 and frozen but
    // for a rim of kPasteBlendPx, and for every pass of the coarser levels inside that rim; a Free
    // band of kCoherentBand pixels around the target (with the rim) lets the surroundings blend in. An
    // exemplar paste needs its polygon inside the exemplar at level 0 only (its pixel centres in the
    // exemplar as resampled to the database spacing): the level-0 pixels are exactly the exemplar's
    // heights + offset; on coarser levels, where a small exemplar may be narrower than the polygon,
    // coordinates are mirrored into the exemplar's interior, or where it has none the synthesized
    // coarse terrain under the paste stays.
    using Paste = PasteConstraint;
    Status paste(const Paste& paste);
    // Freeze brush: marks level-0 pixels (global grid, mask value != 0 and != TypePaint::kUnpainted)
    // frozen for every later update and paste.
    void freeze(const TypePaint& mask);
    // Replaces the frozen mask (per extent pixel, != 0 = frozen) without re-synthesizing: unfreezing
    // changes no height until a later edit reaches the pixels.
    void setFrozen(std::vector<uint8_t> mask);
    // Undoes the copy-paste `paste` in the terrain: the history under its target polygon is
    // forgotten at every level, the frozen mask becomes `frozen_after` (the freeze brush and the
    // other pastes), and the polygon's box plus a band of kCoherentBand pixels is re-synthesized
    // Free, so new terrain fills it coherently with its surroundings.
    Status removePaste(const Paste& paste, std::vector<uint8_t> frozen_after);
    // Level-0 pixels frozen so far by pastes and the freeze brush (per extent pixel, 1 = frozen).
    const std::vector<uint8_t>& frozenMask() const { return frozen_; }
    // The extent's synthesis history (every level and pass), for saving a session.
    const SynthesisHistory& history() const { return *history_; }
    const PixelWindow& extent() const { return extent_; }

    // A terrain restored from saved state: heights, frozen mask and history as history() and
    // frozenMask() gave them for the same extent and params (whose constraints must be those that
    // produced them, lifts included). Errors: sizes that do not fit the extent and params, history
    // atlas indices past the synthesizer's database (saved state is a file: it is checked, not trusted).
    static Result<IncrementalTerrain> restore(Synthesizer& synthesizer, const PixelWindow& extent, SynthesisParams params,
                                              Heightfield heights, std::vector<uint8_t> frozen,
                                              SynthesisHistory history);

    // Undo journal (see the top of this header).
    class Journal {
    public:
        Journal();
        Journal(Journal&&) noexcept;
        Journal& operator=(Journal&&) noexcept;
        ~Journal();
        bool empty() const;
        size_t bytes() const;  // memory it holds
        // Merges a journal recorded after this one: the result undoes both.
        void absorb(Journal&& later);

    private:
        friend class IncrementalTerrain;
        std::unique_ptr<detail::TileJournal> tiles_;
    };
    // Starts recording (a journal already being recorded continues).
    void beginJournal();
    // Stops recording and returns what was recorded since beginJournal().
    Journal takeJournal();
    // Exchanges the recorded tiles with the current state: undo, and applied again, redo. The
    // constraints are not part of the journal: give them back with restoreConstraints().
    void swapJournal(Journal& journal);
    // Sets the constraints that produced the current state (after swapJournal), lifts included.
    void restoreConstraints(std::shared_ptr<const SynthesisConstraints> constraints) {
        params_.constraints = std::move(constraints);
    }

    // Whether update() lifts point and curve constraints (default true); false = the paper's plain
    // targets.
    void holdPointHeights(bool hold) { hold_point_heights_ = hold; }
    // While deferred (and holdPointHeights), edits skip the lift searches and keep the constraints'
    // current lifts, and what they re-synthesize is remembered: the intermediate steps of a drag,
    // where the search was about a quarter of each step. liftDeferred() then lifts the points and
    // curves in that area and re-synthesizes it (`changed`, optional, receives its box; width 0 when
    // nothing was deferred), after which the heights hold as if nothing had been deferred.
    void deferLifts(bool defer) { lifts_deferred_ = defer; }
    bool liftsPending() const { return !deferred_area_.empty(); }
    Status liftDeferred(PixelWindow* changed = nullptr);
    // While deferred, edits also synthesize their finest `levels` levels as a preview
    // (SynthesisParams::preview_levels: upsampled, not corrected, constraints not applied there),
    // and liftDeferred() re-synthesizes everything they changed in full, whether or not points are
    // held. Between the two, heights() is the preview. 0 (default) = deferred edits are full
    // syntheses; 0..2 (1 is what an editor's drag wants: docs/editor.md).
    void setPreviewLevels(int levels);

    // Pixels re-synthesized by the last update (output window only), for benchmarks.
    PixelWindow lastWindow() const { return last_window_; }

private:
    IncrementalTerrain(Synthesizer& s, PixelWindow extent, SynthesisParams params);
    Synthesizer* synthesizer_;
    PixelWindow extent_;
    SynthesisParams params_;
    Heightfield heights_;
    std::shared_ptr<SynthesisHistory> history_;
    PixelWindow last_window_;
    std::vector<uint8_t> frozen_;  // per extent pixel, 1 = frozen (pasted)
    bool hold_point_heights_ = true;
    bool lifts_deferred_ = false;
    PixelWindow deferred_area_{0, 0, 0, 0};  // union of the free areas edited while deferred
    int preview_levels_ = 0;
    bool liftsNow() const { return hold_point_heights_ && !lifts_deferred_; }
    int previewNow() const { return lifts_deferred_ ? preview_levels_ : 0; }
    void noteDeferred(const PixelWindow& free_area);
    std::unique_ptr<detail::TileJournal> journal_;  // recording when set
    // Journal planes: 0 heights, 1 frozen, then 2 + 2 * (level * passes + pass) + {0 index, 1 v}.
    void record(int plane, int64_t x, int64_t y, int64_t w, int64_t h);
    void recordHistory(int level, int64_t gx, int64_t gy, int64_t w, int64_t h);  // every pass, global coords
    Status resynthesize(const PixelWindow& free_area, const std::vector<uint8_t>* free_mask,
                        std::shared_ptr<const SynthesisConstraints> constraints, bool lift_points, int preview_levels = 0);
};

}  // namespace terrasynth
