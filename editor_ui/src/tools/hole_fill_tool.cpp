// holefill: drag an ellipse to re-synthesize it by quilting (Bradbury et al. 2014 s4.4); the three
// variants it offers are shown at once (the previews window) to pick one of and refine from.
#include <memory>

#include <imgui.h>

#include "editor_actions.h"
#include "region_tool.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class HoleFillTool : public RegionTool {
public:
    using RegionTool::RegionTool;

    const char* name() const override { return "holefill"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    void drawPanel() override { ImGui::TextWrapped("Drag an ellipse to fill by quilting; pick one of three variants (s4.4)."); }

private:
    void finish() override {
        const auto to = end();
        if (!to) return;  // a click
        const SessionView& view = editor_.view();
        HoleFillParams fill;
        fill.hole = regionBetween(*track_.press_px, *to, view.extent, RegionShape::Ellipse);
        fill.seed = view.edit_count + 1;
        // The new layer's index: offer its three variants once it exists.
        const int layer = static_cast<int>(view.layers.layers.size());
        editor_.addLayer("hole fill", fill);
        editor_.showHoleFillPreviews(layer, 0);
    }
};

}  // namespace

std::unique_ptr<EditorTool> makeHoleFillTool(EditorActions& editor) { return std::make_unique<HoleFillTool>(editor); }

}  // namespace terrasynth::editor
