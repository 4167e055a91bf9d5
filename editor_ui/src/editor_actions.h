// Private: what the tools, the panels, the shortcuts and the --script player may do to the editor.
//
// EditorApp implements it. Real input reaches it through the tools (mouse over the 3D view), the
// panels and the shortcuts; a script through the same calls and through input injected into the
// host (script_player.h), so a scripted run takes the route a designer's does. Everything runs on
// the main (UI) thread; edits go to the edit thread as requests (terrasynth_editor/edit_worker.h),
// whose `done` callbacks run on this thread before the session's next view is published (view()
// is then still the one the request was made against).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>

#include <osg/Vec2d>
#include <osg/Vec3d>

#include "selection.h"
#include "terrasynth/layers.h"
#include "terrasynth_editor/edit_worker.h"
#include "terrasynth_editor/editor_camera.h"
#include "terrasynth_editor/latency.h"

namespace terrasynth::editor {

class ToolOptions;

class EditorActions {
public:
    virtual ~EditorActions() = default;

    // ---- the session as last published (valid once it opened: tools and panels run only then)
    virtual const SessionView& view() const = 0;
    virtual Selection& selection() = 0;
    virtual CopiedPiece& copiedPiece() = 0;
    virtual ToolOptions& options() = 0;

    // ---- requests to the edit thread
    virtual void submit(EditRequest request) = 0;
    // One step of a measured drag (latency.h): latest wins against the previous step.
    virtual void submitDragStep(InputKind kind, const std::string& label, const std::string& coalesce_key,
                                std::function<Result<PixelWindow>(EditSession&)> run,
                                std::function<void(const EditResult&)> done = {}) = 0;
    // Brackets a drag's steps as one undo step, with previewed steps and deferred lifts
    // (docs/editor.md). timed_release: the release of a point or widget drag, measured as
    // InputKind::DragRelease.
    virtual void beginGesture() = 0;
    virtual void endGesture(bool timed_release = false) = 0;
    // A new layer on top of the stack with the tool's default band weights, selected once added.
    virtual void addLayer(const std::string& name, ToolParams tool) = 0;
    virtual void undo() = 0;
    virtual void redo() = 0;
    virtual void save(const std::string& path) = 0;
    virtual const std::string& savePath() const = 0;  // the project's own file (Ctrl+S)
    virtual void deleteSelection() = 0;
    // Esc: drops the copied piece, every tool's unfinished copy and the selected items.
    virtual void escape() = 0;

    // ---- the 3D view: window pixels (origin top-left) and level-0 pixels (global)
    virtual std::optional<std::pair<double, double>> pickPixel(double x, double y) const = 0;
    virtual std::optional<osg::Vec2d> screenOfPixel(double px, double py) const = 0;
    // The terrain's height as drawn at a level-0 pixel (the extent's mid height where none is drawn).
    virtual float groundAtPixel(double px, double py) const = 0;
    virtual const ScreenProjection& projection() const = 0;
    virtual const EditorCamera* camera() const = 0;  // null before the terrain is shown
    // Top-down on `centre` (world), `width_m` across; orbiting it from `distance_m`.
    virtual void viewAerial(const osg::Vec3d& centre, double width_m) = 0;
    virtual void viewFree(const osg::Vec3d& centre, double distance_m, double heading_deg, double pitch_deg) = 0;

    // ---- the editor's state
    // Selects the tool of that name (false: there is none); a drag of the previous tool is dropped.
    virtual bool selectTool(const std::string& name) = 0;
    virtual void setStatus(const std::string& text, bool error) = 0;
    // Shows the three variants of the hole-fill layer at `layer` for `generation` (s4.4).
    virtual void showHoleFillPreviews(int layer, int generation) = 0;
};

}  // namespace terrasynth::editor
