// The editor's command line (CLI11) and its autosave's name.
#include "terrasynth_editor/editor_options.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include <CLI/CLI.hpp>

#include "terrasynth/checked_number.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth_flags/flag_checks.h"
#include "terrasynth_plugin/plugin_options.h"

namespace terrasynth::editor {
namespace {

Status parseSizeText(const std::string& text, int* w, int* h) {
    const size_t x = text.find('x');
    int a = 0, b = 0;
    char rest = 0;
    if (x == std::string::npos || std::sscanf(text.c_str(), "%dx%d%c", &a, &b, &rest) != 2)
        return Status::error("--size: expected WxH, got '" + text + "'");
    if (a < 320 || b < 240 || a > 8192 || b > 8192) return Status::error("--size: must be within 320x240..8192x8192, got " + text);
    *w = a, *h = b;
    return Status::ok();
}

Status parseColour(const std::string& text, float* rgb) {
    const Status bad = Status::error("--clear-color: expected R,G,B, each " + finiteRangeText(0, 1) + ", got '" + text + "'");
    size_t at = 0;
    for (int i = 0; i < 3; ++i) {
        const size_t comma = i < 2 ? text.find(',', at) : text.size();
        if (comma == std::string::npos) return bad;
        auto v = parseFiniteNumber(text.substr(at, comma - at), 0.0, 1.0);
        if (!v) return bad;
        rgb[i] = static_cast<float>(*v);
        at = comma + 1;
    }
    return Status::ok();
}

}  // namespace

Result<EditorOptions> parseEditorOptions(int argc, const char* const* argv, std::string* help) {
    EditorOptions o;
    std::string size, backend = "opencl", colour;
    CLI::App app("terrasynth_editor: edit a terrasynth project inside the 3D view", "terrasynth_editor");
    app.add_option("project", o.project, "Project file (.tsyn)")->required();
    app.add_option("--script", o.script, "Play timed input from FILE, then exit (docs/editor.md)");
    app.add_option("--stats", o.stats, "Write latency and frame statistics (JSON) at exit");
    app.add_flag("--recover", o.recover, "Open the project's autosave when it is newer than the project");
    app.add_option("--size", size, "Window size WxH (default 1280x720)");
    app.add_option("--backend", backend, "Synthesis backend: opencl or reference");
    app.add_option("--clear-color", colour, "Background colour R,G,B in [0, 1]");
    app.add_option("--ui-scale", o.ui_scale, "Panel scale")->check(flags::FiniteRange(0.5, 4.0));
    app.add_option("--drag-preview-levels", o.drag_preview_levels,
                   "Finest levels a drag shows uncorrected until release (0 = full quality every step; default 1)")
        ->check(flags::FiniteRange(0, 2));
    app.add_option("--terrain-options", o.terrain_options,
                   "Terrain settings in the plugin's syntax, e.g. \"tileSize=128 pixelError=6\"");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        if (help) *help = app.help();
        return EditorOptions{};
    } catch (const CLI::ParseError& e) {
        return Status::error(e.what());
    }
    if (!size.empty())
        if (Status s = parseSizeText(size, &o.width, &o.height); !s) return s;
    // Written at exit, so checked now (as the game does): a run must not end in a failed write.
    if (!o.stats.empty())
        if (Status s = FileTransaction::checkTarget(o.stats); !s) return s.withContext("--stats");
    if (!colour.empty())
        if (Status s = parseColour(colour, o.clear_color); !s) return s;
    auto terrain = plugin::parsePluginOptions(std::string(kTerrainDefaults) + " " + o.terrain_options);
    if (!terrain) return Status::error("--terrain-options: " + terrain.message());
    if (Status s = plugin::validateOptions(terrain->node); !s) return Status::error("--terrain-options: " + s.message());
    if (backend == "opencl") o.synthesizer.backend = SynthesisBackend::OpenCL;
    else if (backend == "reference") o.synthesizer.backend = SynthesisBackend::Reference;
    else return Status::error("--backend: must be opencl or reference, got '" + backend + "'");
    return o;
}

float terrainPixelError(const std::string& gl_renderer) {
    for (const char* software : {"llvmpipe", "softpipe", "swrast", "Software Rasterizer"})
        if (gl_renderer.find(software) != std::string::npos) return 12.0f;
    return 6.0f;
}

std::string autosavePath(const std::string& project_path) {
    std::filesystem::path p(project_path);
    p.replace_extension();
    return p.string() + ".autosave.tsyn";
}

std::string newerAutosave(const std::string& project_path) {
    namespace fs = std::filesystem;
    const std::string autosave = autosavePath(project_path);
    std::error_code e1, e2;
    const auto saved = fs::last_write_time(autosave, e1);
    const auto project = fs::last_write_time(project_path, e2);
    if (e1 || e2 || saved <= project) return "";
    return autosave;
}

}  // namespace terrasynth::editor
