// freeze: drag to freeze ground, whose heights then survive later edits (Gain et al. 2015 s5.3), or
// to unfreeze it.
#include <imgui.h>

#include "brush_tool.h"

namespace terrasynth::editor {
namespace {

class FreezeTool : public tools::BrushTool {
public:
    using BrushTool::BrushTool;

    const char* name() const override { return "freeze"; }
    ToolGroup group() const override { return ToolGroup::Synthesis; }

    void drawPanel() override {
        ImGui::TextWrapped("Drag to freeze: frozen ground keeps its heights (s5.3).");
        drawBrushOptions("unfreeze");
    }

protected:
    EditRequest strokeRequest(const Polyline& stroke, float radius, bool erase) override {
        EditRequest r;
        r.label = erase ? "unfreeze" : "freeze";
        r.run = [stroke, radius, erase](EditSession& s) { return erase ? s.unfreeze(stroke, radius) : s.freeze(stroke, radius); };
        return r;
    }
};

}  // namespace

std::unique_ptr<EditorTool> makeFreezeTool(EditorActions& editor) { return std::make_unique<FreezeTool>(editor); }

}  // namespace terrasynth::editor
