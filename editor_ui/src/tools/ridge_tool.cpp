// ridge: sketch a ridge line, which becomes a ridge layer (Bradbury et al. 2014 s4.2: a Gaussian
// cross-section of the given width under a constant crest height).
#include <memory>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "overlay.h"
#include "tool_kit.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class RidgeTool : public EditorTool {
public:
    explicit RidgeTool(EditorActions& editor)
        : editor_(editor),
          height_m_(editor.options().number("ridge.height", 400.0f)),
          width_px_(editor.options().number("ridge.width", 10.0f)) {}

    const char* name() const override { return "ridge"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    bool press(const osg::Vec2d& at, int) override {
        sketch_.press(editor_, at);
        sketching_ = true;
        return true;
    }
    void drag(const osg::Vec2d& at) override { sketch_.drag(editor_, at); }

    void release(const osg::Vec2d&) override {
        sketching_ = false;
        const double screen_length = sketch_.screenLength(editor_);
        const Polyline stroke = decimate(sketch_.stroke_px, kCourseSpacingPx);
        sketch_.stroke_px.clear();
        if (stroke.size() < 2 || screen_length < kMinStrokeScreenPx) return;  // a click
        const PixelWindow& extent = editor_.view().extent;
        RidgeParams ridge;
        for (const auto& p : stroke) ridge.points.push_back({p.first - extent.x, p.second - extent.y});
        ridge.profile_m = {height_m_};
        ridge.width_px = width_px_;
        editor_.addLayer("ridge", ridge);
    }

    void abandon() override {
        sketching_ = false;
        sketch_.stroke_px.clear();
    }

    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (active && sketching_) painter.drape(sketch_.stroke_px, false, overlay_colours::kSketch, 2.0f);
    }

    void drawPanel() override {
        ImGui::TextWrapped("Drag to sketch a ridge line.");
        ImGui::DragFloat("height (m)", &height_m_, 5.0f, 10.0f, 5000.0f, "%.0f");
        ImGui::DragFloat("width (px)", &width_px_, 0.5f, 1.0f, 200.0f, "%.0f");
    }

private:
    EditorActions& editor_;
    float& height_m_;  // the crest above the terrain below
    float& width_px_;  // shared with the perspective tool's strokes
    SketchStroke sketch_;
    bool sketching_ = false;
};

}  // namespace

std::unique_ptr<EditorTool> makeRidgeTool(EditorActions& editor) { return std::make_unique<RidgeTool>(editor); }

}  // namespace terrasynth::editor
