// paint: drag to paint a database terrain type (Gain et al. 2015 s5.2), or to erase painted types.
#include <algorithm>

#include <imgui.h>

#include "brush_tool.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {

class PaintTool : public tools::BrushTool {
public:
    explicit PaintTool(EditorActions& editor)
        : BrushTool(editor),
          type_(editor.options().choice(
              "paint.type", 0, [e = &editor] { return e->view().database->type_names; }, "type")) {}

    const char* name() const override { return "paint"; }
    ToolGroup group() const override { return ToolGroup::Synthesis; }

    void drawPanel() override {
        ImGui::TextWrapped("Drag to paint a terrain type (s5.2).");
        const std::vector<std::string>& types = editor_.view().database->type_names;
        if (!types.empty()) {
            type_ = std::clamp(type_, 0, static_cast<int>(types.size()) - 1);
            if (ImGui::BeginCombo("type", types[static_cast<size_t>(type_)].c_str())) {
                for (size_t i = 0; i < types.size(); ++i)
                    if (ImGui::Selectable(types[i].c_str(), static_cast<int>(i) == type_)) type_ = static_cast<int>(i);
                ImGui::EndCombo();
            }
        }
        drawBrushOptions("erase");
    }

protected:
    EditRequest strokeRequest(const Polyline& stroke, float radius, bool erase) override {
        const std::vector<std::string>& types = editor_.view().database->type_names;
        const std::string type = types.at(static_cast<size_t>(std::clamp(type_, 0, int(types.size()) - 1)));
        EditRequest r;
        r.label = erase ? "erase types" : "paint " + type;
        r.run = [stroke, radius, erase, type](EditSession& s) {
            return erase ? s.eraseTypes(stroke, radius) : s.paintTypes(stroke, radius, type);
        };
        return r;
    }

private:
    int& type_;  // database type id
};

}  // namespace

std::unique_ptr<EditorTool> makePaintTool(EditorActions& editor) { return std::make_unique<PaintTool>(editor); }

}  // namespace terrasynth::editor
