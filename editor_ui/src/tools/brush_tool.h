// Private: a brush dragged over the terrain that edits along its whole stroke (the paint and freeze
// tools). Each drag step submits the stroke so far, latest wins: brushing the same pixels again
// changes nothing, so the session only re-synthesizes what is newly covered. The drag is one gesture.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "editor_tool.h"
#include "tool_kit.h"

namespace terrasynth::editor::tools {

class BrushTool : public EditorTool {
public:
    // Paint and freeze share one brush: the options brush.radius and brush.erase.
    explicit BrushTool(EditorActions& editor);

    bool press(const osg::Vec2d& at, int mods) override;
    void drag(const osg::Vec2d& at) override;
    void release(const osg::Vec2d& at) override;
    void hover(const osg::Vec2d& at) override;
    void abandon() override;
    void drawOverlay(OverlayPainter& painter, bool active) override;

protected:
    // The request for the stroke so far (level-0 pixels), with its label and what it runs.
    virtual EditRequest strokeRequest(const Polyline& stroke, float radius_px, bool erase) = 0;
    // The brush's size and erase box (the erase box's label is the tool's).
    void drawBrushOptions(const char* erase_label);

    EditorActions& editor_;
    float& radius_px_;
    bool& erase_;

private:
    DragTrack track_;
    Polyline stroke_px_;
    bool dragging_ = false;
    std::optional<std::pair<double, double>> hover_px_;
};

}  // namespace terrasynth::editor::tools
