// Private: the editor program (one window, one session). The frame loop, the shortcuts, the input
// routed to the tools and the session's requests are in editor_app.cpp, the panels in panels.cpp /
// panel_layers.cpp / panel_exemplars.cpp, the 3D overlays in overlay.cpp. The tools are classes of
// their own (tools/editor_tool.h) and the --script player too (script_player.h); both reach the
// editor only through EditorActions, which EditorApp implements. Everything here runs on the main
// (UI) thread; the session is only touched through EditWorker.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>
#include <osg/Group>

#include "editor_actions.h"
#include "script_player.h"
#include "selection.h"
#include "tool_options.h"
#include "tools/editor_tool.h"
#include "terrasynth/project.h"
#include "terrasynth_editor/edit_worker.h"
#include "terrasynth_editor/editor_camera.h"
#include "terrasynth_editor/editor_options.h"
#include "terrasynth_editor/latency.h"
#include "terrasynth_editor/script.h"
#include "terrasynth_host/host_window.h"
#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::editor {

class EditorApp final : public EditorActions, public EditorProbe {
public:
    // `project` loaded and checked; `database` when it could be loaded before the window (null: the
    // session builds it, with progress shown); `recover_from`: an autosave to open instead.
    EditorApp(host::HostWindow& host, EditorOptions options, Project project, std::vector<ScriptCommand> script,
              std::shared_ptr<const ExemplarDatabase> database, std::string recover_from);
    ~EditorApp() override;
    // Runs until the window closes or the script ends; returns the exit code.
    int run();

    // ---- EditorActions (editor_actions.h)
    const SessionView& view() const override { return *view_; }
    Selection& selection() override { return selection_; }
    CopiedPiece& copiedPiece() override { return copied_; }
    ToolOptions& options() override { return tool_options_; }
    void submit(EditRequest request) override;
    void submitDragStep(InputKind kind, const std::string& label, const std::string& coalesce_key,
                        std::function<Result<PixelWindow>(EditSession&)> run,
                        std::function<void(const EditResult&)> done = {}) override;
    void beginGesture() override;
    void endGesture(bool timed_release = false) override;
    void addLayer(const std::string& name, ToolParams tool) override;
    void undo() override;
    void redo() override;
    void save(const std::string& path) override;
    const std::string& savePath() const override { return save_path_; }
    void deleteSelection() override;
    void escape() override;
    std::optional<std::pair<double, double>> pickPixel(double x, double y) const override;
    std::optional<osg::Vec2d> screenOfPixel(double px, double py) const override;
    float groundAtPixel(double px, double py) const override;
    const ScreenProjection& projection() const override { return projection_; }
    const EditorCamera* camera() const override { return camera_.get(); }
    void viewAerial(const osg::Vec3d& centre, double width_m) override;
    void viewFree(const osg::Vec3d& centre, double distance_m, double heading_deg, double pitch_deg) override;
    bool selectTool(const std::string& name) override;
    void setStatus(const std::string& text, bool error) override;
    void showHoleFillPreviews(int layer, int generation) override;

    // ---- EditorProbe (script_player.h)
    bool ready() const override;
    bool settled() const override;
    bool idle() const override { return worker_->idle(); }
    void collectResults() override { onResults(); }
    int errorsSinceCheck() const override { return errors_since_check_; }
    const std::string& lastError() const override { return last_error_; }
    void clearErrors() override { errors_since_check_ = 0; }
    bool autosaveHoldsTheLastEdit() const override;
    int selectedLayer() const override { return selection_.layer; }
    std::optional<ImVec4> itemRect(const std::string& id) const override;
    void setPhase(const std::string& name) override;

private:
    // ---- frame loop and session requests (editor_app.cpp)
    void startOpening(const std::string& path_to_open);
    void frame();
    void onResults();
    void ensureTerrain();
    void handleInput();
    void autosaveTick();
    void writeStats();
    void stepHistory(bool forward);
    std::optional<osg::Vec3d> pickWorld(double x, double y) const;
    // Adds the tile work since the phase started (TerrainStats deltas) to `tiles`.
    void addPhaseTiles(const plugin::TerrainStats& now, TileAccounting& tiles) const;

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
    void releasePreviewImages();

    // ---- overlays over the 3D view (overlay.cpp)
    void drawOverlays();

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

    // Tools, their options, the selection and the copied piece.
    ToolOptions tool_options_;
    std::vector<std::unique_ptr<EditorTool>> tools_;
    EditorTool* tool_ = nullptr;  // the active one
    bool tool_dragging_ = false;  // the active tool follows a drag (its press returned true)
    Selection selection_;
    CopiedPiece copied_;
    // Hole fill previews (s4.4): layer index, generation, three pictures.
    int previews_layer_ = -1, previews_generation_ = 0;
    bool previews_pending_ = false;
    std::vector<ImTextureID> preview_images_;
    std::vector<ImTextureID> exemplar_images_;
    std::vector<ImVec2> exemplar_sizes_;
    int thumbnail_lasso_ = -1;  // exemplar being lassoed in the panel
    Polyline thumbnail_lasso_px_;

    bool* show_reach_ = nullptr;  // the option overlay.reach
    bool show_types_ = true;
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
    double unsaved_since_s_ = -1.0;  // when an edit the autosave lacks was first seen; -1: none
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

    std::unique_ptr<ScriptPlayer> script_;  // null: interactive
    int exit_code_ = kExitOk;
    std::string renderer_;
};

}  // namespace terrasynth::editor
