// terrasynth_editor/editor_options.h: the editor's command line and where its autosave lives.
//
//   terrasynth_editor PROJECT.tsyn [--script FILE] [--stats OUT.json] [--recover] [--size WxH]
//                     [--backend opencl|reference] [--clear-color R,G,B] [--ui-scale S]
//                     [--terrain-options "tileSize=64 pixelError=8 ..."]
//
// Exit codes: 0 done, 1 the editor failed (no window, a failed save or screenshot in a script),
// 2 bad input (options, project, script), which is reported before any window opens.
#pragma once

#include <string>

#include "terrasynth/status.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::editor {

struct EditorOptions {
    std::string project;
    std::string script;  // "" = interactive
    std::string stats;   // "" = no report
    bool recover = false;
    int width = 1280, height = 720;
    SynthesizerOptions synthesizer;
    float clear_color[3] = {0.62f, 0.72f, 0.85f};
    float ui_scale = 1.0f;
    // The terrain node's settings, in the plugin's option syntax (terrasynth_plugin/plugin_options.h),
    // over the editor's defaults (kTerrainDefaults).
    std::string terrain_options;
    // Autosaves are at least this far apart, and wait for this long without input...
    double autosave_interval_s = 1.0;
    // ...but no edit waits longer than this for one: while input goes on without such a pause, the
    // autosave is written between two gestures (what kill -9 can lose: the edits of this span).
    double autosave_max_delay_s = 10.0;
    // A drag's intermediate steps synthesize their finest levels as a preview (upsampled, not
    // corrected: EditSession::setDragPreviewLevels); the release re-synthesizes in full. 0..2.
    int drag_preview_levels = 1;
};

constexpr int kExitOk = 0, kExitFailed = 1, kExitBadInput = 2;

// The editor's terrain settings before --terrain-options: tiles small enough that an edit rebuilds
// little more than its changed window, two workers (the edit thread and the rasterizer need the rest
// of a small machine); the pixel error is chosen by the renderer (terrainPixelError).
constexpr const char* kTerrainDefaults = "tileSize=64 threads=2";
// Screen-space error for `gl_renderer` (GL_RENDERER): 12 px on a software rasterizer (Mesa llvmpipe,
// softpipe, swrast), where triangles cost CPU the edits need; 6 px on a GPU.
float terrainPixelError(const std::string& gl_renderer);

// Parses argv; on --help, `help` receives the usage text and the result is an ok empty project.
// Errors name the option.
Result<EditorOptions> parseEditorOptions(int argc, const char* const* argv, std::string* help = nullptr);

// "<dir>/world.tsyn" -> "<dir>/world.autosave.tsyn".
std::string autosavePath(const std::string& project_path);
// The autosave of `project_path` when it exists and was written after the project; "" otherwise.
std::string newerAutosave(const std::string& project_path);

}  // namespace terrasynth::editor
