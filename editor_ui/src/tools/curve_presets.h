// Private: the curve tool's widget presets (a ridge, a valley, a cliff), which the curve inspector
// also applies to a selected curve (panels.cpp). Defined in curve_tool.cpp.
#pragma once

#include <vector>

#include "terrasynth/constraints.h"
#include "terrasynth_editor/sketch_geometry.h"

namespace terrasynth::editor {

class EditorActions;

enum class CurvePreset { Ridge = 0, Valley = 1, Cliff = 2 };
constexpr int kCurvePresets = 3;
const char* curvePresetName(CurvePreset preset);  // "ridge", "valley", "cliff"

// Widgets at the start, middle and end of `course` (level-0 pixels) with the preset's shape:
// `height_m` above (valley: below) the ground under each, reaching `reach_px` to both sides.
std::vector<CurveWidget> presetWidgets(const Polyline& course, CurvePreset preset, float height_m, float reach_px,
                                       const EditorActions& editor);

}  // namespace terrasynth::editor
