// noise: drag an ellipse for a layer of local fractal detail, or click for detail everywhere
// (Bradbury et al. 2014, Figures 1 and 12).
#include <memory>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "tool_kit.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class NoiseTool : public EditorTool {
public:
    explicit NoiseTool(EditorActions& editor)
        : editor_(editor),
          amplitude_m_(editor.options().number("noise.amplitude", 60.0f)),
          wavelength_px_(editor.options().number("noise.wavelength", 48.0f)) {}

    const char* name() const override { return "noise"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    bool press(const osg::Vec2d& at, int) override {
        region_.press(editor_, at);
        return true;
    }
    void drag(const osg::Vec2d& at) override { region_.drag(at); }

    void release(const osg::Vec2d&) override {
        region_.active = false;
        const SessionView& view = editor_.view();
        NoiseParams noise;
        noise.fractal.amplitude_m = amplitude_m_;
        noise.fractal.wavelength_px = wavelength_px_;
        noise.fractal.octaves = 6;
        noise.fractal.seed = view.edit_count + 1;
        if (const auto end = region_.end(editor_))
            noise.region = regionBetween(*region_.track.press_px, *end, view.extent, RegionShape::Ellipse);
        noise.feather_px = 16.0;
        editor_.addLayer("noise", noise);
    }

    void abandon() override { region_.active = false; }
    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (active) region_.draw(editor_, painter);
    }

    void drawPanel() override {
        ImGui::TextWrapped("Drag an ellipse for local fractal detail, or click for everywhere.");
        ImGui::DragFloat("amplitude (m)", &amplitude_m_, 1.0f, 1.0f, 2000.0f, "%.0f");
        ImGui::DragFloat("wavelength (px)", &wavelength_px_, 1.0f, 2.0f, 1024.0f, "%.0f");
    }

private:
    EditorActions& editor_;
    float& amplitude_m_;
    float& wavelength_px_;
    RegionDrag region_;
};

}  // namespace

std::unique_ptr<EditorTool> makeNoiseTool(EditorActions& editor) { return std::make_unique<NoiseTool>(editor); }

}  // namespace terrasynth::editor
