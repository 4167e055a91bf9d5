// peak: click to raise a peak layer (Bradbury et al. 2014 s4.2); Shift digs a pit.
#include <memory>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {

class PeakTool : public EditorTool {
public:
    explicit PeakTool(EditorActions& editor)
        : editor_(editor),
          height_m_(editor.options().number("peak.height", 800.0f)),
          spread_px_(editor.options().number("peak.spread", 24.0f)) {}

    const char* name() const override { return "peak"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    bool press(const osg::Vec2d& at, int mods) override {
        const auto px = editor_.pickPixel(at.x(), at.y());
        if (!px) return false;
        const PixelWindow& extent = editor_.view().extent;
        PeakParams peak;
        peak.center_x = px->first - extent.x;
        peak.center_y = px->second - extent.y;
        peak.height_m = (mods & GLFW_MOD_SHIFT) ? -height_m_ : height_m_;
        peak.spread_px = spread_px_;
        editor_.addLayer("peak", peak);
        return false;
    }

    void drawPanel() override {
        ImGui::TextWrapped("Click to raise a peak (Shift: dig a pit).");
        ImGui::DragFloat("height (m)", &height_m_, 10.0f, 10.0f, 5000.0f, "%.0f");
        ImGui::DragFloat("spread (px)", &spread_px_, 0.5f, 2.0f, 300.0f, "%.0f");
    }

private:
    EditorActions& editor_;
    float& height_m_;
    float& spread_px_;
};

}  // namespace

std::unique_ptr<EditorTool> makePeakTool(EditorActions& editor) { return std::make_unique<PeakTool>(editor); }

}  // namespace terrasynth::editor
