// Private: the editor program (one window, one session). The frame loop and the session's requests
// are in editor_app.cpp, the tools in tools.cpp, the panels in panels.cpp / panel_layers.cpp /
// panel_exemplars.cpp, the 3D overlays in overlay.cpp and the --script player in script_player.cpp.
// Everything here runs on the main (UI) thread; the session is only touched through EditWorker.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>
#include <osg/Group>

#include "terrasynth/project.h"
#include "terrasynth_editor/edit_worker.h"
#include "terrasynth_editor/editor_camera.h"
#include "terrasynth_editor/editor_options.h"
#include "terrasynth_editor/latency.h"
#include "terrasynth_editor/script.h"
#include "terrasynth_editor/sketch_geometry.h"
#include "terrasynth_host/host_window.h"
#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::editor {

enum class Tool { Point, Curve, Paint, Freeze, Paste, Peak, Ridge, LayerPaste, HoleFill, Noise, Perspective };
constexpr Tool kTools[] = {Tool::Point, Tool::Curve, Tool::Paint, Tool::Freeze, Tool::Paste, Tool::Peak,
                           Tool::Ridge, Tool::LayerPaste, Tool::HoleFill, Tool::Noise, Tool::Perspective};
// Script and panel names: "point", "curve", ...
const char* toolName(Tool tool);
std::optional<Tool> toolFromName(const std::string& name);

enum class CurvePreset { Ridge = 0, Valley = 1, Cliff = 2 };

// What new constraints and layers get (the tools panel and `set KEY VALUE` in scripts).
struct ToolOptions {
    float point_raise_m = 300.0f;  // a new point's height above the ground it is put on
    float point_radius_px = 64.0f;
    float point_slope_deg = 0.0f, point_slope_direction_deg = 0.0f;
    CurvePreset curve_preset = CurvePreset::Ridge;
    float curve_height_m = 250.0f;  // the preset's crest (ridge, cliff top) or trough depth
    float curve_reach_px = 32.0f;
    bool curve_spline = true;
    float brush_radius_px = 12.0f;
    int paint_type = 0;  // database type id
    bool erase = false;  // paint: erase types; freeze: unfreeze
    float paste_offset_m = 0.0f;
    float peak_height_m = 800.0f, peak_spread_px = 24.0f;
    float ridge_height_m = 400.0f, ridge_width_px = 10.0f;
    float noise_amplitude_m = 60.0f, noise_wavelength_px = 48.0f;
};

class EditorApp {
public:
    // `project` loaded and checked; `database` when it could be loaded before the window (null: the
    // session builds it, with progress shown); `recover_from`: an autosave to open instead.
    EditorApp(host::HostWindow& host, EditorOptions options, Project project, std::vector<ScriptCommand> script,
              std::shared_ptr<const ExemplarDatabase> database, std::string recover_from);
    ~EditorApp();
    // Runs until the window closes or the script ends; returns the exit code.
    int run();

private:
    // ---- frame loop and session requests (editor_app.cpp)
    void startOpening(const std::string& path_to_open);
    void frame();
    void onResults();
    void ensureTerrain();
    void handleInput();
    void autosaveTick();
    void writeStats();
    void submit(EditRequest request);
    // One step of a measured drag (latency.h): latest wins against the previous step.
    void submitDragStep(InputKind kind, const std::string& label, const std::string& coalesce_key,
                        std::function<Result<PixelWindow>(EditSession&)> run,
                        std::function<void(const EditResult&)> done = {});
    void stepHistory(bool forward);
    void beginGesture();
    // timed_release: the release of a point or widget drag, timed as InputKind::DragRelease.
    void endGesture(bool timed_release = false);
    void undo();
    void redo();
    void save(const std::string& path);
    void setStatus(const std::string& text, bool error);
    bool settled() const;
    // Adds the tile work since the phase started (TerrainStats deltas) to `tiles`.
    void addPhaseTiles(const plugin::TerrainStats& now, TileAccounting& tiles) const;
    void setPhase(const std::string& name);

    // ---- tools (tools.cpp)
    void toolPress(double x, double y, int mods);
    void toolDrag(double x, double y);
    void toolRelease(double x, double y);
    void toolHover(double x, double y);
    void deleteSelection();
    std::optional<osg::Vec3d> pickWorld(double x, double y) const;
    std::optional<std::pair<double, double>> pickPixel(double x, double y) const;  // level-0, global
    std::optional<osg::Vec2d> screenOfPixel(double px, double py) const;
    float groundAtPixel(double px, double py) const;
    void finishSketch();
    void finishRegion();
    void finishPerspectiveStroke();
    void placePaste(double dx, double dy, std::optional<EditId> replacing);
    // A new layer on top of the stack with the tool's default band weights, selected once added.
    void addLayer(const std::string& name, ToolParams tool);
    void movePointTo(EditId id, double px, double py);
    void moveWidgetTo(double px, double py);
    std::vector<CurveWidget> presetWidgets(const Polyline& course) const;

    // ---- panels (panels.cpp, panel_layers.cpp, panel_exemplars.cpp)
    void drawPanels();
    void drawMenuBar();
    void drawToolPanel();
    void drawInspector();
    void drawPointInspector(const PointItem& point);
    void drawCurveInspector(const CurveItem& curve);
    void drawPasteInspector(const PasteItem& paste);
    void drawLayersPanel();
    void drawLayerParams(int index, const EditLayer& layer);
    void drawBandSliders(const std::string& id, BandWeights weights, int layer_index);
    void drawHoleFillPreviews();
    void drawExemplarsPanel();
    void drawStatusBar();
    void drawOpeningScreen();
    void drawRecoverPrompt();
    void noteItem(const std::string& id);
    // ImGui items that edit continuously (sliders): a gesture while active, one request per change.
    void trackGesture(const std::string& id);
    float& liveValue(const std::string& key, float current);

    // ---- overlays over the 3D view (overlay.cpp)
    void drawOverlays();

    // ---- --script (script_player.cpp)
    void scriptStep();
    bool runScriptCommand(const ScriptCommand& c);  // false: wait (call again next frame)
    void scriptFail(const ScriptCommand& c, const std::string& why);

    host::HostWindow& host_;
    EditorOptions options_;
    Project project_;
    std::string save_path_;      // where Ctrl+S writes (the project's own file)
    std::string autosave_path_;
    std::shared_ptr<const ExemplarDatabase> preloaded_;
    std::string recover_from_;
    bool asking_recover_ = false;

    std::unique_ptr<EditWorker> worker_;
    std::shared_ptr<const SessionView> view_;
    osg::ref_ptr<osg::Group> root_;
    osg::ref_ptr<plugin::TerrainNode> terrain_;
    osg::ref_ptr<EditorCamera> camera_;
    ScreenProjection projection_;
    double frame_input_s_ = 0.0;  // when this frame's input was polled

    // Tools and selection.
    Tool tool_ = Tool::Point;
    ToolOptions tool_options_;
    struct Drag {
        enum class Kind { None, MovePoint, Sketch, Brush, MoveWidget, Lasso, MovePaste, PlacePaste, Region, Perspective };
        Kind kind = Kind::None;
        osg::Vec2d press_screen, last_screen;
        std::optional<std::pair<double, double>> press_px;
        Polyline stroke_px;                  // level-0 picks along the drag
        std::vector<osg::Vec2d> stroke_screen;
        bool gesture = false;
    } drag_;
    std::optional<std::pair<double, double>> hover_px_;
    EditId selected_point_ = 0, selected_curve_ = 0, selected_paste_ = 0;
    int selected_widget_ = -1, selected_layer_ = -1;
    // Copy-paste source: a lasso on the terrain (exemplar -1) or on an exemplar thumbnail.
    Polyline paste_source_;
    int paste_exemplar_ = -1;
    std::optional<std::pair<double, double>> ghost_offset_px_;
    // Layer paste (s4.3): the source rectangle, then a click places it.
    std::optional<Region> layer_paste_source_;
    // Hole fill previews (s4.4): layer index, generation, three pictures.
    int previews_layer_ = -1, previews_generation_ = 0;
    bool previews_pending_ = false;
    std::vector<ImTextureID> preview_images_;
    std::vector<ImTextureID> exemplar_images_;
    std::vector<ImVec2> exemplar_sizes_;
    int thumbnail_lasso_ = -1;  // exemplar being lassoed in the panel
    Polyline thumbnail_lasso_px_;

    bool show_reach_ = true, show_types_ = true;
    bool free_view_ = true;

    // Status, saving, autosave.
    std::string status_;
    bool status_error_ = false;
    int errors_since_check_ = 0;
    std::string last_error_;
    uint64_t user_saved_count_ = 0;
    double last_autosave_s_ = -1e9;
    double last_input_s_ = -1e9;
    uint64_t autosaved_count_ = 0;
    bool autosave_queued_ = false;
    std::vector<double> autosave_ms_;
    bool open_failed_reported_ = false;
    int gestures_open_ = 0;

    // Measurements (--stats).
    LatencyTracker latency_;
    PhasedFrames frames_;
    TileAccounting tiles_;
    plugin::TerrainStats phase_start_stats_;
    std::string phase_ = "setup";

    // Panels' item rectangles this frame (script `item ID`).
    std::map<std::string, ImVec4> items_;
    std::map<std::string, bool> active_gestures_;
    std::map<std::string, float> live_values_;

    // --script.
    std::vector<ScriptCommand> script_;
    size_t script_pc_ = 0;
    struct ScriptWait {
        int frames = 0;
        double until_s = 0.0;
        double deadline_s = 0.0;
        int drag_step = -1;
        int settle_frames = 0;
        bool started = false;
    } wait_;
    bool script_done_ = false;
    bool script_yield_ = false;
    int exit_code_ = kExitOk;
    std::string renderer_;
};

}  // namespace terrasynth::editor
