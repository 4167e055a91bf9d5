// terrasynth_editor/script.h: the --script file: timed input and checks for tests and benchmarks.
//
// One command per line; '#' starts a comment. Coordinates are window pixels (origin top-left)
// unless said otherwise; input commands are injected through the host (HostWindow::inject*), so they
// take the route real input takes (ImGui first, then the tools and the camera), one step per frame.
//
//   wait FRAMES                      let frames pass
//   sleep MS                         let wall time pass (frames keep running)
//   settle [TIMEOUT_S]               until no edit is queued or running, the terrain has every tile
//                                    it wants and every input has reached the screen (default 120 s)
//   view aerial X Y WIDTH_M          top-down view centred on level-0 pixel (X, Y), WIDTH_M across
//   view free X Y DISTANCE_M HEADING_DEG PITCH_DEG   orbit view around level-0 pixel (X, Y)
//   tool NAME                        the tool of that name, as on its button (point, curve, ...;
//                                    docs/editor.md lists them)
//   set KEY VALUE                    a tool option (docs/editor.md lists them); the value is
//                                    the rest of the line
//   move X Y | press [BUTTON] | release [BUTTON] | click [BUTTON]     BUTTON: left right middle
//   drag X0 Y0 X1 Y1 [STEPS]         press at (X0, Y0), STEPS moves (default 10), release
//   item ID [DX DY]                  move the pointer to the centre of a panel item (+ offset);
//                                    handles in the 3D view are items too: handle.point.N,
//                                    handle.widget.N (of the selected curve)
//   drag-item ID DX DY [STEPS]       press on an item's centre, move by (DX, DY), release
//   key SPEC                         e.g. ctrl+z, ctrl+shift+z, ctrl+s, delete, escape
//   scroll STEPS                     mouse wheel at the pointer
//   screenshot FILE [ui|3d]          with the panels (default) or the 3D view alone
//   save [FILE]                      Ctrl+S, or save as FILE
//   heights FILE                     the session's extent heights (float32 + sidecar, .f32)
//   undo-all                         Ctrl+Z until there is nothing left to undo
//   wait-autosave                    until the autosave holds the current edit
//   expect-error TEXT                the last edit failed with a message containing TEXT
//   expect-ok                        no edit failed since the start or the last expect-*
//   expect-selected-layer INDEX      once idle, the layer panel selects layer INDEX (-1: none)
//   phase NAME                       label the following frames in the --stats report
//   echo TEXT                        print TEXT on stdout
//   quit                             stop (the end of the script stops too)
#pragma once

#include <string>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth::editor {

struct ScriptCommand {
    std::string op;                 // the command word
    std::vector<std::string> args;  // the rest of the line, split on blanks (echo: the whole rest)
    std::vector<double> numbers;    // args parsed as numbers where the command takes numbers
    int line = 0;                   // 1-based, for messages
};

// Checks every line (command, argument count, numbers); errors name the file and line:
// "demo.script:3: drag: needs X0 Y0 X1 Y1 [STEPS]".
Result<std::vector<ScriptCommand>> parseScript(const std::string& text, const std::string& path_for_messages);
Result<std::vector<ScriptCommand>> readScript(const std::string& path);

// "ctrl+shift+z" -> GLFW key and modifier bits; false when the key is unknown.
bool parseKeySpec(const std::string& spec, int* glfw_key, int* glfw_mods);

}  // namespace terrasynth::editor
