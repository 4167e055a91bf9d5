// Private: drawing over the 3D view with ImGui's background draw list (no GL here). Shapes given in
// level-0 pixels are draped on the terrain as drawn (TerrainNode::heightAt, through
// EditorActions::screenOfPixel), subdivided so they follow the relief.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <imgui.h>
#include <osg/Vec2d>

#include "terrasynth_editor/sketch_geometry.h"

namespace terrasynth::editor {

class EditorActions;

namespace overlay_colours {
constexpr ImU32 kExtent = IM_COL32(255, 255, 255, 90);
constexpr ImU32 kHandle = IM_COL32(255, 210, 60, 255), kSelected = IM_COL32(255, 80, 60, 255);
constexpr ImU32 kReach = IM_COL32(255, 210, 60, 110);
constexpr ImU32 kCourse = IM_COL32(80, 200, 255, 255), kBand = IM_COL32(80, 200, 255, 90);
constexpr ImU32 kJunction = IM_COL32(255, 60, 200, 255);
constexpr ImU32 kPaste = IM_COL32(170, 255, 120, 220), kGhost = IM_COL32(170, 255, 120, 120);
constexpr ImU32 kSketch = IM_COL32(255, 255, 255, 230);
}  // namespace overlay_colours

class OverlayPainter {
public:
    // `items`: where handles with an item id are recorded for scripts (`item handle.point.0`).
    OverlayPainter(const EditorActions& editor, std::map<std::string, ImVec4>& items);

    // A polyline of level-0 pixels on the terrain; `closed` joins the last point to the first.
    void drape(const Polyline& line, bool closed, ImU32 colour, float thickness);
    // A circle of radius `r` level-0 pixels around (cx, cy), on the terrain.
    void circle(double cx, double cy, double r, ImU32 colour, float thickness);
    // A filled handle at a level-0 pixel, `radius` window pixels; `item` names it for scripts.
    void handle(double px, double py, ImU32 colour, float radius, const std::string& item = "");
    // A ring of `radius` window pixels around a level-0 pixel (junctions).
    void ring(double px, double py, float radius, ImU32 colour, float thickness);
    // A polyline in window pixels (a stroke drawn on the screen itself).
    void screenPolyline(const std::vector<osg::Vec2d>& points, ImU32 colour, float thickness);

private:
    // Whether `vertices` more fit the draw list: Debian's Dear ImGui indexes vertices in 16 bits, and
    // its OpenGL2 backend cannot split a list (no RendererHasVtxOffset), so past 65,536 vertices
    // ImGui aborts the editor (a project of ~250 points did). What does not fit is left undrawn.
    bool room(int vertices);

    const EditorActions& editor_;
    std::map<std::string, ImVec4>& items_;
    ImDrawList* draw_list_;
    double sample_px_;  // drape subdivision, level-0 pixels
};

}  // namespace terrasynth::editor
