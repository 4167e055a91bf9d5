// The editor's tools in the left panel's order (synthesis tools first, then layer tools). Each is
// defined in its own file by the factory named here; a new tool is one more line in this list.
#include "editor_tool.h"

#define TERRASYNTH_EDITOR_TOOLS(TOOL) \
    TOOL(makePointTool)               \
    TOOL(makeCurveTool)               \
    TOOL(makePaintTool)               \
    TOOL(makeFreezeTool)              \
    TOOL(makePasteTool)               \
    TOOL(makePeakTool)                \
    TOOL(makeRidgeTool)               \
    TOOL(makeLayerPasteTool)          \
    TOOL(makeHoleFillTool)            \
    TOOL(makeNoiseTool)               \
    TOOL(makePerspectiveTool)         \
    TOOL(makeFlattenTool)             \
    /* a new tool: one more line above this one */

namespace terrasynth::editor {

#define TERRASYNTH_DECLARE_TOOL(factory) std::unique_ptr<EditorTool> factory(EditorActions& editor);
TERRASYNTH_EDITOR_TOOLS(TERRASYNTH_DECLARE_TOOL)
#undef TERRASYNTH_DECLARE_TOOL

std::vector<std::unique_ptr<EditorTool>> makeEditorTools(EditorActions& editor) {
    std::vector<std::unique_ptr<EditorTool>> tools;
#define TERRASYNTH_MAKE_TOOL(factory) tools.push_back(factory(editor));
    TERRASYNTH_EDITOR_TOOLS(TERRASYNTH_MAKE_TOOL)
#undef TERRASYNTH_MAKE_TOOL
    return tools;
}

}  // namespace terrasynth::editor
