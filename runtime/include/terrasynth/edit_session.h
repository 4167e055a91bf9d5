// terrasynth/edit_session.h: the terrain being edited, as one object every front end drives (the
// in-engine editor, the demo game, the CLI, scripts).
//
// An EditSession owns a project, its exemplar database, an incremental terrain (coherent local
// re-synthesis, Gain et al. 2015 s5.3) and a layer editor (Bradbury et al. 2014). Every edit is one
// call that returns the level-0 window whose final heights changed (empty: nothing changed) or a
// Status naming the problem, in which case nothing changed. Every edit is undoable exactly: after
// undo() the heights are bit-identical to those before the step, after redo() to those after it.
// A gesture (a drag of 30 intermediate positions) is one step when bracketed by
// beginGesture()/endGesture().
//
// The world: the project's extent holds the edited heights; around it (and under it at coarser
// levels) the world is the *reference* synthesis, that of the project's constraints as the session
// was opened (or re-seeded). Outside the extent the world therefore stays put while the designer
// edits inside, and coarser levels add the block mean of the edit, so the plugin's LOD tiles agree
// with the edited extent and meet the untouched world where the edit fades out.
//
// Saving writes the .tsyn (constraints and layers written back, painting and freeze as mask PNGs
// beside it) and an edited-heights sidecar beside it (docs/project-format.md): incremental results
// depend on the order of the edits, so the saved constraints alone would not give what the designer
// saw. Terrain::open, the plugin and `terrasynth synth` read the sidecar while its digest matches the
// project, and warn and re-synthesize when it does not.
//
// Coordinates are global level-0 pixels (terrasynth/grid.h; x east, y south), heights metres.
//
// Threading: the edit calls, undo/redo, save and the accessors returning references are for one
// thread at a time (an editor's edit thread). heightSource(), heightAt(), heightsAt(), editCount()
// and isDirty() may be called from any thread at any time: each edit publishes an immutable snapshot
// of the extent, and those read the latest one (heightSource() binds the snapshot current when it is
// called, so a tile build never mixes two edits: call it again after each edit).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "terrasynth/grid.h"
#include "terrasynth/layers.h"
#include "terrasynth/project.h"

namespace terrasynth {

struct EditSessionOptions {
    SynthesizerOptions synthesizer;
    DatabaseBuildOptions database;  // when the database cache must be (re)built
    // The undo history's bounds: at most max_undo_steps steps (1..256) holding at most
    // max_undo_bytes of memory together (undoBytes()); beyond either the oldest steps are dropped
    // first, and undo() then stops at the oldest kept. The newest step is kept whatever its size.
    // A constraint edit's step holds the re-synthesized windows of every level, a re-seed's the
    // whole extent's synthesis (docs/limits.md, "Long sessions").
    int max_undo_steps = 100;
    size_t max_undo_bytes = size_t{1} << 30;
    // The project's database when the caller already has it (must be the one the project names);
    // null: the session opens it (loadOrBuild of the project's cache).
    std::shared_ptr<const ExemplarDatabase> preloaded_database;
    // Told about recoverable surprises while opening, e.g. a sidecar whose digest no longer matches
    // its project (the session then re-synthesizes). Null: they are only kept in warnings().
    std::function<void(const std::string&)> on_warning;
};

// Stable identity of a point, curve or paste within one session (not saved; a reopened project gets
// new ids in list order). 0 is never an id.
using EditId = uint64_t;

class EditSession {
public:
    // Opens a project: builds or loads its database, then the edited extent: from the project's
    // edited-heights sidecar when its digest matches, otherwise by synthesizing the project afresh
    // (as Terrain does). Errors name the file and field.
    static Result<std::unique_ptr<EditSession>> open(const std::string& project_path, const EditSessionOptions& options = {});
    static Result<std::unique_ptr<EditSession>> fromProject(Project project, const EditSessionOptions& options = {});
    ~EditSession();
    EditSession(const EditSession&) = delete;
    EditSession& operator=(const EditSession&) = delete;

    // ---- State (edit thread) ----
    // The project with every edit written back: constraints_json, layers_json, the seed.
    const Project& project() const;
    const ExemplarDatabase& database() const;
    std::shared_ptr<const ExemplarDatabase> databasePtr() const;
    PixelWindow extent() const;
    GridFrame frame() const;
    // The extent's final level-0 heights (synthesis, then layers), extent-sized.
    const Heightfield& heights() const;
    // The current constraints (points with their lifts, curves, painting, freeze brush, pastes).
    const SynthesisConstraints& constraints() const;
    const LayerStack& layers() const;
    std::vector<EditId> pointIds() const;
    std::vector<EditId> curveIds() const;
    std::vector<EditId> pasteIds() const;
    // Null when the id is unknown.
    const PointConstraint* point(EditId id) const;
    const CurveConstraint* curve(EditId id) const;
    const PasteConstraint* paste(EditId id) const;
    // Warnings from opening (sidecar problems), oldest first.
    const std::vector<std::string>& warnings() const;

    // ---- Edits (edit thread). Each returns the changed level-0 window or an error with nothing
    // changed. Fields are checked like the project file's (constraints.h): a point's height within
    // +-12000 m, slope angle 0..80, radius > 0, sites and courses within +-1e8 pixels, ...
    Result<PixelWindow> addPoint(const PointConstraint& point, EditId* id = nullptr);
    Result<PixelWindow> movePoint(EditId id, double x, double y);
    // Replaces every field the user sets (site, height, slope direction and angle, radius).
    Result<PixelWindow> setPoint(EditId id, const PointConstraint& point);
    Result<PixelWindow> removePoint(EditId id);
    Result<PixelWindow> addCurve(const CurveConstraint& curve, EditId* id = nullptr);
    // Replaces the whole curve (over-sketching a course, the spline toggle).
    Result<PixelWindow> setCurve(EditId id, const CurveConstraint& curve);
    Result<PixelWindow> removeCurve(EditId id);
    Result<PixelWindow> moveCoursePoint(EditId id, int index, double x, double y);
    // Inserts the widget in order of t.
    Result<PixelWindow> addWidget(EditId curve, const CurveWidget& widget);
    // Moves widget `index` along the course to `t` (0..1); widgets stay sorted by t.
    Result<PixelWindow> moveWidget(EditId curve, int index, double t);
    Result<PixelWindow> setWidget(EditId curve, int index, const CurveWidget& widget);
    Result<PixelWindow> removeWidget(EditId curve, int index);
    // Type painting (s5.2): a round brush of `radius_px` along `stroke` with a database type name;
    // eraseTypes makes the pixels unpainted again.
    Result<PixelWindow> paintTypes(const std::vector<std::pair<double, double>>& stroke, double radius_px,
                                   const std::string& type_name);
    Result<PixelWindow> eraseTypes(const std::vector<std::pair<double, double>>& stroke, double radius_px);
    // The freeze brush (s5.3): frozen pixels keep their heights through later edits. Freezing and
    // unfreezing change no height themselves (the returned window is empty).
    Result<PixelWindow> freeze(const std::vector<std::pair<double, double>>& stroke, double radius_px);
    Result<PixelWindow> unfreeze(const std::vector<std::pair<double, double>>& stroke, double radius_px);
    // Copy-paste (s5.3, fig. 8): see PasteConstraint. The pasted pixels are frozen. Removing a paste
    // unfreezes its pixels and synthesizes new terrain there, coherent with its surroundings.
    Result<PixelWindow> addPaste(const PasteConstraint& paste, EditId* id = nullptr);
    Result<PixelWindow> removePaste(EditId id);
    // Any set of constraints at once, as one coherent edit: only the reach of what differs is
    // re-synthesized (what `terrasynth synth --coherent-with` does). A changed freeze brush applies
    // first (so what it newly covers holds); pastes must be unchanged (addPaste, removePaste).
    Result<PixelWindow> setConstraints(const SynthesisConstraints& next);
    // A new seed: the whole extent is synthesized afresh (constraints kept), and the reference
    // world with it: the returned window is the extent, but the world outside changed too (a front
    // end invalidates everything). Undoing or redoing a re-seed does the same.
    Result<PixelWindow> reseed(uint32_t seed);

    // The layer stack (layers.h LayerEditor operations; indices into layers().layers).
    Result<PixelWindow> addLayer(EditLayer layer, int index = -1);
    Result<PixelWindow> removeLayer(int index);
    Result<PixelWindow> moveLayer(int from, int to);
    Result<PixelWindow> setLayerVisible(int index, bool visible);
    Result<PixelWindow> setLayerWeights(int index, BandWeights weights);
    Result<PixelWindow> setBaseWeights(BandWeights weights);
    Result<PixelWindow> replaceLayer(int index, EditLayer layer);
    Result<PixelWindow> setLayerBase(BaseLayer base);
    Result<PixelWindow> setBandSplit(BandSplit split);
    Result<PixelWindow> mergeLayerDown(int index);
    // The whole stack at once (a preset, or another version of the project's layers).
    Result<PixelWindow> setLayers(LayerStack stack);
    // The three variants a hole-fill layer offers (LayerEditor::holeFillPreviews); not an edit.
    Result<std::vector<Heightfield>> holeFillPreviews(int index, int generation);

    // ---- Drags (edit thread) ----
    // While deferred, edits keep the points' and curves' lifts instead of searching them
    // (IncrementalTerrain::deferLifts), so a drag's intermediate steps cost about a quarter less and
    // their sites may miss their heights by what the move changed. liftDeferred() is the edit that
    // lifts everything they re-synthesized (empty window when nothing was deferred): call it when
    // the drag ends, before endGesture() so it is part of the drag's undo step.
    void deferLifts(bool defer);
    Result<PixelWindow> liftDeferred();
    // While deferred, the steps also synthesize their finest `levels` levels as a preview
    // (IncrementalTerrain::setPreviewLevels: upsampled from the level above, not corrected, so a
    // point drag step costs about half) and liftDeferred() re-synthesizes their area in full, so
    // the finished gesture is a full synthesis. 0 (default) = every step is a full synthesis; 0..2.
    void setDragPreviewLevels(int levels);

    // ---- Undo (edit thread) ----
    // Everything between the two calls is one undo step (nesting counts; an empty gesture adds none).
    void beginGesture();
    void endGesture();
    bool canUndo() const;
    bool canRedo() const;
    // The window that changed, empty when there was nothing to undo or redo.
    Result<PixelWindow> undo();
    Result<PixelWindow> redo();
    // Memory held by the undo and redo steps, bytes (bounded by EditSessionOptions::max_undo_bytes
    // after each edit; redo steps come from undone ones, so they stay within it too).
    size_t undoBytes() const;

    // ---- Reading the world (any thread) ----
    // Heights of any window and level of the world as it is now (see the top of this header).
    // Level 0 inside the extent is bit-exact with heights(); outside it and at coarser levels it is
    // the reference synthesis plus the block mean of the edit.
    HeightSource heightSource() const;
    // Creates the calling thread's synthesizer now rather than on its first read, as
    // Terrain::prepareThisThread does (terrain.h says why): a front end's tile workers call it before
    // its frame loop starts. Errors: those of creating a synthesizer (no OpenCL device, kernel build).
    Status prepareThisThread() const;
    // Level-0 height at world point (x east, y north, metres), bilinear between the four samples
    // around it (exact: the samples are the world's). About 0.1 us when those samples are inside the
    // extent; elsewhere it synthesizes a 2x2 window (milliseconds).
    Result<double> heightAt(double world_x, double world_y) const;
    Result<std::vector<double>> heightsAt(const std::vector<std::array<double, 2>>& world_points) const;
    // Edits applied so far (undo and redo count too): a cheap "has anything changed" check.
    uint64_t editCount() const;

    // ---- Saving (edit thread) ----
    // Writes `path` (.tsyn) with its masks and edited-heights sidecar beside it, all or nothing
    // (FileTransaction); the session then belongs to `path`. Errors name the file; a failed save
    // leaves the session dirty and the files on disk as they were.
    Status save(const std::string& path);
    // save(path) if anything changed since the last save or open; otherwise returns at once
    // (cheap enough to call every second). `saved` (optional) tells whether it wrote.
    Status saveIfDirty(const std::string& path, bool* saved = nullptr);
    bool isDirty() const;

    struct Impl;  // opaque (runtime/src/project/edit_session_impl.h)

private:
    explicit EditSession(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace terrasynth
