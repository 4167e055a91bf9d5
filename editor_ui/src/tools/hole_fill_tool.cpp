// holefill: drag an ellipse to re-synthesize it by quilting (Bradbury et al. 2014 s4.4); the three
// variants it offers are shown at once (the previews window) to pick one of and refine from.
#include <memory>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "tool_kit.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class HoleFillTool : public EditorTool {
public:
    explicit HoleFillTool(EditorActions& editor) : editor_(editor) {}

    const char* name() const override { return "holefill"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    bool press(const osg::Vec2d& at, int) override {
        region_.press(editor_, at);
        return true;
    }
    void drag(const osg::Vec2d& at) override { region_.drag(at); }

    void release(const osg::Vec2d&) override {
        region_.active = false;
        const auto end = region_.end(editor_);
        if (!end) return;  // a click
        const SessionView& view = editor_.view();
        HoleFillParams fill;
        fill.hole = regionBetween(*region_.track.press_px, *end, view.extent, RegionShape::Ellipse);
        fill.seed = view.edit_count + 1;
        // The new layer's index: offer its three variants once it exists.
        const int layer = static_cast<int>(view.layers.layers.size());
        editor_.addLayer("hole fill", fill);
        editor_.showHoleFillPreviews(layer, 0);
    }

    void abandon() override { region_.active = false; }
    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (active) region_.draw(editor_, painter);
    }

    void drawPanel() override { ImGui::TextWrapped("Drag an ellipse to fill by quilting; pick one of three variants (s4.4)."); }

private:
    EditorActions& editor_;
    RegionDrag region_;
};

}  // namespace

std::unique_ptr<EditorTool> makeHoleFillTool(EditorActions& editor) { return std::make_unique<HoleFillTool>(editor); }

}  // namespace terrasynth::editor
