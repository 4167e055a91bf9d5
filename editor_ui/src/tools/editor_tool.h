// Private: one tool of the editor's left panel (Gain et al. 2015 s3, s5; Bradbury et al. 2014 s4).
//
// A tool gets the left button over the 3D view (what ImGui does not take): press, then drag and
// release while it follows a drag, hover otherwise. It edits only through EditorActions (requests
// to the edit thread, the selection, gestures), draws its cursor and unfinished work over the 3D
// view with an OverlayPainter and its options with ImGui; no GL calls, no session access. A
// finished interaction is one undo step: one request, or a drag's requests inside a gesture.
//
// Adding a tool: one file tools/<name>_tool.cpp with a class deriving from EditorTool and a factory
// `std::unique_ptr<EditorTool> make<Name>Tool(EditorActions&)`, and its line in tool_registry.cpp.
// Its options come from EditorActions::options() (keys "<name>.<option>"; docs/editor.md lists them).
#pragma once

#include <memory>
#include <vector>

#include <osg/Vec2d>

namespace terrasynth::editor {

class EditorActions;
class OverlayPainter;

// The left panel's two sections.
enum class ToolGroup { Synthesis, Layers };

class EditorTool {
public:
    virtual ~EditorTool() = default;

    // The name on its button, in scripts (`tool NAME`) and in the status bar: "point", "curve", ...
    virtual const char* name() const = 0;
    virtual ToolGroup group() const = 0;

    // A left press at `at` (window pixels, origin top-left); `mods`: GLFW modifier bits. Returns
    // whether the tool follows this drag (drag() for every move, then release()); false when the
    // press was the whole interaction (a click that adds something, or nothing under the pointer).
    virtual bool press(const osg::Vec2d& at, int mods) = 0;
    // The pointer moved during the tool's drag; also called once at the release's position.
    virtual void drag(const osg::Vec2d& at) {}
    // The end of the tool's drag (after drag() at the same position).
    virtual void release(const osg::Vec2d& at) {}
    // The pointer moved with no drag of the tool under way (the active tool only).
    virtual void hover(const osg::Vec2d& at) {}
    // Another tool was selected during a drag: forget it (a gesture it began is ended).
    virtual void abandon() {}
    // Esc: drop an unfinished copy (a copied rectangle waiting for its click).
    virtual void escape() {}

    // Over the 3D view, every frame, for every tool: what it has pending (a copied piece) and, when
    // `active`, its cursor and its drag in progress.
    virtual void drawOverlay(OverlayPainter& painter, bool active) {}
    // Its options below the tool buttons (ImGui widgets; only the active tool's).
    virtual void drawPanel() = 0;
};

// Every tool, in the panel's order (tool_registry.cpp).
std::vector<std::unique_ptr<EditorTool>> makeEditorTools(EditorActions& editor);

}  // namespace terrasynth::editor
