#include "brush_tool.h"

#include <imgui.h>

#include "overlay.h"
#include "tool_options.h"

namespace terrasynth::editor::tools {

BrushTool::BrushTool(EditorActions& editor)
    : editor_(editor),
      radius_px_(editor.options().number("brush.radius", 12.0f)),
      erase_(editor.options().flag("brush.erase", false)) {}

bool BrushTool::press(const osg::Vec2d& at, int) {
    track_.start(editor_, at);
    stroke_px_.clear();
    if (!track_.press_px) return false;
    stroke_px_.push_back(*track_.press_px);
    editor_.beginGesture();
    dragging_ = true;
    drag(at);
    return true;
}

void BrushTool::drag(const osg::Vec2d& at) {
    const bool moved = track_.moved(at);
    if (auto now = editor_.pickPixel(at.x(), at.y()); now && (moved || stroke_px_.size() == 1)) {
        if (stroke_px_.size() > 1 || now != stroke_px_.front()) stroke_px_.push_back(*now);
        EditRequest r = strokeRequest(stroke_px_, radius_px_, erase_);
        r.coalesce_key = "brush";
        r.refresh_masks = true;
        editor_.submit(std::move(r));
    }
    track_.follow(at);
}

void BrushTool::release(const osg::Vec2d&) {
    editor_.endGesture();
    dragging_ = false;
    stroke_px_.clear();
}

void BrushTool::hover(const osg::Vec2d& at) { hover_px_ = editor_.pickPixel(at.x(), at.y()); }

void BrushTool::abandon() {
    if (dragging_) editor_.endGesture();
    dragging_ = false;
    stroke_px_.clear();
}

void BrushTool::drawOverlay(OverlayPainter& painter, bool active) {
    if (!active) return;
    const auto at = dragging_ && !stroke_px_.empty() ? std::optional(stroke_px_.back()) : hover_px_;
    if (at) painter.circle(at->first, at->second, radius_px_, overlay_colours::kSketch, 1.5f);
}

void BrushTool::drawBrushOptions(const char* erase_label) {
    ImGui::DragFloat("brush (px)", &radius_px_, 0.5f, 1.0f, 200.0f, "%.0f");
    ImGui::Checkbox(erase_label, &erase_);
}

}  // namespace terrasynth::editor::tools
