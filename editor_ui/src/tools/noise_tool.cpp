// noise: drag an ellipse for a layer of local fractal detail, or click for detail everywhere
// (Bradbury et al. 2014, Figures 1 and 12).
#include <memory>

#include <imgui.h>

#include "editor_actions.h"
#include "region_tool.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class NoiseTool : public RegionTool {
public:
    explicit NoiseTool(EditorActions& editor)
        : RegionTool(editor),
          amplitude_m_(editor.options().number("noise.amplitude", 60.0f)),
          wavelength_px_(editor.options().number("noise.wavelength", 48.0f)) {}

    const char* name() const override { return "noise"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    void drawPanel() override {
        ImGui::TextWrapped("Drag an ellipse for local fractal detail, or click for everywhere.");
        ImGui::DragFloat("amplitude (m)", &amplitude_m_, 1.0f, 1.0f, 2000.0f, "%.0f");
        ImGui::DragFloat("wavelength (px)", &wavelength_px_, 1.0f, 2.0f, 1024.0f, "%.0f");
    }

private:
    void finish() override {
        const SessionView& view = editor_.view();
        NoiseParams noise;
        noise.fractal.amplitude_m = amplitude_m_;
        noise.fractal.wavelength_px = wavelength_px_;
        noise.fractal.octaves = 6;
        noise.fractal.seed = view.edit_count + 1;
        if (const auto to = end()) noise.region = regionBetween(*track_.press_px, *to, view.extent, RegionShape::Ellipse);
        noise.feather_px = 16.0;
        editor_.addLayer("noise", noise);
    }

    float& amplitude_m_;
    float& wavelength_px_;
};

}  // namespace

std::unique_ptr<EditorTool> makeNoiseTool(EditorActions& editor) { return std::make_unique<NoiseTool>(editor); }

}  // namespace terrasynth::editor
