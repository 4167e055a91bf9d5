// EditorApp: the frame loop, the terrain and camera, shortcuts and the input routed to the active
// tool, requests to the edit thread, picking, saving and autosave, and the --stats report.
#include "editor_app.h"

#include <algorithm>
#include <cstdio>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <osg/NodeCallback>

#include "terrasynth/heightfield_io.h"
#include "terrasynth_plugin/plugin_options.h"
#include "terrasynth_plugin/terrain_look.h"

namespace terrasynth::editor {
namespace {

// Runs `after` once the UPDATE traversal below the node is done: tiles merged this frame are in the
// graph and nothing has been culled or drawn yet.
struct AfterUpdate : osg::NodeCallback {
    std::function<void()> after;
    explicit AfterUpdate(std::function<void()> f) : after(std::move(f)) {}
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override {
        traverse(node, nv);
        after();
    }
};

// The overlay colour of frozen pixels (the last type colour slot, see EditWorker's type source).
const osg::Vec3 kFrozenColour(0.55f, 0.85f, 1.0f);

}  // namespace

EditorApp::EditorApp(host::HostWindow& host, EditorOptions options, Project project, std::vector<ScriptCommand> script,
                     std::shared_ptr<const ExemplarDatabase> database, std::string recover_from)
    : host_(host),
      options_(std::move(options)),
      project_(std::move(project)),
      preloaded_(std::move(database)),
      recover_from_(std::move(recover_from)) {
    tools_ = makeEditorTools(*this);
    tool_ = tools_.front().get();
    show_reach_ = &tool_options_.flag("overlay.reach", true);
    if (!script.empty()) script_ = std::make_unique<ScriptPlayer>(std::move(script), options_.script, *this, *this, host_);
    save_path_ = project_.path;
    autosave_path_ = autosavePath(project_.path);
    root_ = new osg::Group;
    host_.viewer().setSceneData(root_.get());
    // A newer autosave: --recover opens it; interactively the designer is asked; a script goes on.
    const std::string newer = newerAutosave(project_.path);
    if (!recover_from_.empty()) {
        startOpening(recover_from_);
    } else if (!newer.empty() && !script_) {
        recover_from_ = newer;
        asking_recover_ = true;
    } else {
        if (!newer.empty())
            std::printf("terrasynth_editor: %s is newer than the project (run with --recover to open it)\n", newer.c_str());
        startOpening(project_.path);
    }
}

EditorApp::~EditorApp() {
    // The edit thread first: it may still hand the terrain a height source.
    worker_.reset();
    releasePreviewImages();
    for (ImTextureID t : exemplar_images_) host_.releaseImage(t);
}

void EditorApp::startOpening(const std::string& path_to_open) {
    Project project = project_;
    const bool recovering = path_to_open != project_.path;
    EditSessionOptions o;
    o.synthesizer = options_.synthesizer;
    o.preloaded_database = preloaded_;
    o.on_warning = [](const std::string& w) { std::fprintf(stderr, "terrasynth_editor: warning: %s\n", w.c_str()); };
    if (recovering) std::printf("terrasynth_editor: recovering %s\n", path_to_open.c_str());
    worker_ = std::make_unique<EditWorker>([project, path_to_open, recovering, o](const auto& progress) mutable
                                           -> Result<std::unique_ptr<EditSession>> {
        if (recovering) {
            auto recovered = loadProject(path_to_open);
            if (!recovered) return recovered.status();
            project = std::move(recovered.value());
        }
        o.database.progress = progress;
        progress("synthesizing the extent", 0.0);
        return EditSession::fromProject(std::move(project), o);
    });
}

int EditorApp::run() {
    renderer_ = host_.glRenderer();
    for (;;) {
        const bool open = host_.beginFrame();
        frame_input_s_ = steadySeconds();
        if (!open || (script_ && script_->done())) {
            host_.endFrame();
            break;
        }
        frame();
        const host::FrameTiming t = host_.endFrame();
        latency_.afterFrame(steadySeconds());
        if (terrain_) frames_.add(phase_, t);
    }
    if (script_ && script_->failed()) exit_code_ = kExitFailed;
    if (worker_ && worker_->state() == EditWorker::State::Failed && exit_code_ == kExitOk) exit_code_ = kExitBadInput;
    // Closing the window never loses work: what the autosave does not hold yet is written now.
    if (worker_ && worker_->state() == EditWorker::State::Ready && !script_) {
        for (int i = 0; i < gestures_open_; ++i) endGesture();  // a drag's too: the tool sees no release
        tool_dragging_ = false;
        worker_->waitIdle(600.0);
        worker_->takeResults();
        if (worker_->editCount() != autosaved_count_ && worker_->editCount() != user_saved_count_) {
            last_autosave_s_ = last_input_s_ = -1e9;
            autosaveTick();
            worker_->waitIdle(600.0);
            worker_->takeResults();
        }
    }
    if (!options_.stats.empty()) writeStats();
    return exit_code_;
}

void EditorApp::frame() {
    items_.clear();

    projection_ = ScreenProjection::of(*host_.viewer().getCamera(), host_.width(), host_.height());
    if (camera_) camera_->setAspect(double(host_.width()) / host_.height());
    if (asking_recover_) {
        drawRecoverPrompt();
    } else if (worker_->state() != EditWorker::State::Ready) {
        drawOpeningScreen();
        if (worker_->state() == EditWorker::State::Failed && !open_failed_reported_) {
            open_failed_reported_ = true;
            std::fprintf(stderr, "terrasynth_editor: %s\n", worker_->openError().c_str());
            exit_code_ = kExitBadInput;
            if (script_) script_->stop();
        }
    } else {
        onResults();
        ensureTerrain();
        handleInput();
        drawPanels();
        drawOverlays();
        autosaveTick();
    }
    if (script_ && !script_->done() && !asking_recover_) script_->step();
}

void EditorApp::onResults() {
    for (const EditResult& r : worker_->takeResults([this] { view_ = worker_->view(); })) {
        latency_.noteResult(r);
        if (!r.status) {
            ++errors_since_check_;
            last_error_ = r.status.message();
            setStatus(r.label + " failed: " + r.status.message(), true);
            std::fprintf(stderr, "terrasynth_editor: %s failed: %s\n", r.label.c_str(), r.status.message().c_str());
        }
        if (r.status && !r.changed.empty() && !options_.script.empty())
            std::printf("terrasynth_editor: %s: changed %lld %lld %d %d\n", r.label.c_str(), static_cast<long long>(r.changed.x),
                        static_cast<long long>(r.changed.y), r.changed.width, r.changed.height);
        if (r.generation != 0 && phase_ != "setup") {
            ++tiles_.edits;
            tiles_.touching += r.tiles_marked;
            tiles_.in_view += r.tiles_drawn;
        }
    }
    view_ = worker_->view();
}

void EditorApp::ensureTerrain() {
    if (terrain_) return;
    view_ = worker_->view();
    const SessionView& v = *view_;
    const double extent_m = std::max(v.extent.width, v.extent.height) * v.frame.meters_per_pixel;
    // The editor's defaults, the renderer's pixel error, a draw radius of two extents, tiles up to the
    // coarsest synthesized level (coarser ones are block averages costing 4^d times the synthesis,
    // and their builds took the cores the edit thread needs: mean tile build 15-17 ms against 10-13),
    // then the user's.
    const int max_level = std::max(0, std::min({6, v.database->levelCount() - 1, v.coarsest_synthesized_level}));
    const std::string settings = std::string(kTerrainDefaults) + " pixelError=" + std::to_string(terrainPixelError(renderer_)) +
                                 " viewRadius=" + std::to_string(2.0 * extent_m) + " maxLevel=" + std::to_string(max_level) +
                                 " " + options_.terrain_options;
    auto parsed = plugin::parsePluginOptions(settings);  // checked with the command line
    const plugin::TerrainNodeOptions o = parsed ? parsed->node : plugin::TerrainNodeOptions{};
    terrain_ = new plugin::TerrainNode(worker_->heightSource(), v.frame.meters_per_pixel, o);
    // Each tile worker makes its synthesizer before the first frame that draws tiles, as the osgDB
    // reader and the game do (docs/plugin.md): no OpenCL context is made while a frame is drawn or
    // the window closes. A failure here is the edit thread's too, which reported it when it opened.
    if (Status s = terrain_->runOnEveryWorker([this] { return worker_->prepareThisThread(); }); !s)
        std::fprintf(stderr, "terrasynth_editor: tile workers: %s\n", s.message().c_str());
    worker_->attachTerrain(terrain_);
    plugin::TerrainLook look = plugin::lookForHeightRange(v.min_height_m, v.max_height_m);
    look.type_colours[plugin::TerrainLook::kTypeColours - 1] = kFrozenColour;
    look.type_colour_mix = show_types_ ? 0.5f : 0.0f;
    terrain_->setLook(look);
    root_->addChild(terrain_.get());
    root_->setUpdateCallback(new AfterUpdate([this] {
        plugin::TerrainNode* t = terrain_.get();
        latency_.afterUpdate([t](uint64_t generation) { return t->tilesAwaitingRebuild(generation); }, steadySeconds());
    }));

    camera_ = new EditorCamera(host_.options().fovy_deg, double(host_.width()) / host_.height());
    camera_->setGroundHeight([t = terrain_.get()](double x, double y) { return t->heightAt(x, y); });
    const GridFrame& f = v.frame;
    const osg::Vec3d centre(f.worldX(v.extent.x + 0.5 * v.extent.width), f.worldY(v.extent.y + 0.5 * v.extent.height),
                            0.5 * (v.min_height_m + v.max_height_m));
    camera_->setFree(centre, 1.1 * extent_m, 0.0, 40.0);
    host_.viewer().setCameraManipulator(camera_.get(), false);

}

void EditorApp::handleInput() {
    // Any input, to ImGui or to the tools, postpones the autosave.
    if (!host_.routedEvents().empty() || ImGui::IsAnyItemActive() || ImGui::GetIO().MouseDelta.x != 0.0f ||
        ImGui::GetIO().MouseDelta.y != 0.0f)
        last_input_s_ = frame_input_s_;
    for (const host::InputEvent& e : host_.routedEvents()) {
        using T = host::InputEvent::Type;
        const osg::Vec2d at(e.x, e.y);
        if (e.type == T::KeyDown || e.type == T::KeyRepeat) {
            const bool ctrl = e.mods & GLFW_MOD_CONTROL, shift = e.mods & GLFW_MOD_SHIFT;
            if (tool_dragging_) continue;  // no shortcuts in the middle of a drag
            if (ctrl && e.key == GLFW_KEY_Z) shift ? redo() : undo();
            else if (ctrl && e.key == GLFW_KEY_Y) redo();
            else if (ctrl && e.key == GLFW_KEY_S && e.type == T::KeyDown) save(save_path_);
            else if ((e.key == GLFW_KEY_DELETE || e.key == GLFW_KEY_BACKSPACE) && e.type == T::KeyDown) deleteSelection();
            else if (e.key == GLFW_KEY_ESCAPE && e.type == T::KeyDown) escape();
        } else if (e.type == T::MouseDown && e.button == 0) {
            tool_dragging_ = tool_->press(at, e.mods);
        } else if (e.type == T::MouseMove) {
            if (tool_dragging_) tool_->drag(at);
            else tool_->hover(at);
        } else if (e.type == T::MouseUp && e.button == 0 && tool_dragging_) {
            tool_->drag(at);
            tool_dragging_ = false;
            tool_->release(at);
        }
    }
}

bool EditorApp::selectTool(const std::string& name) {
    for (const auto& tool : tools_)
        if (name == tool->name()) {
            if (tool_dragging_) tool_->abandon();
            tool_dragging_ = false;
            tool_ = tool.get();
            return true;
        }
    return false;
}

void EditorApp::escape() {
    copied_.clear();
    for (const auto& tool : tools_) tool->escape();
    selection_.clearItems();
}

void EditorApp::deleteSelection() {
    if (auto r = selection_.takeDeletion()) submit(std::move(*r));
}

std::optional<osg::Vec3d> EditorApp::pickWorld(double x, double y) const {
    if (!terrain_ || !view_) return std::nullopt;
    osg::Vec3d origin, direction;
    projection_.ray(x, y, &origin, &direction);
    const double mpp = view_->frame.meters_per_pixel;
    const double extent_m = std::max(view_->extent.width, view_->extent.height) * mpp;
    plugin::TerrainNode* t = terrain_.get();
    return pickTerrain(origin, direction, [t](double wx, double wy) { return t->heightAt(wx, wy); }, 0.5 * mpp,
                       10.0 * extent_m + camera_->distance());
}

std::optional<std::pair<double, double>> EditorApp::pickPixel(double x, double y) const {
    const auto world = pickWorld(x, y);
    if (!world) return std::nullopt;
    return std::make_pair(view_->frame.pixelX(world->x()), view_->frame.pixelY(world->y()));
}

float EditorApp::groundAtPixel(double px, double py) const {
    const GridFrame& f = view_->frame;
    if (terrain_)
        if (auto h = terrain_->heightAt(f.worldX(px), f.worldY(py))) return *h;
    return 0.5f * (view_->min_height_m + view_->max_height_m);
}

std::optional<osg::Vec2d> EditorApp::screenOfPixel(double px, double py) const {
    const GridFrame& f = view_->frame;
    return projection_.toScreen(osg::Vec3d(f.worldX(px), f.worldY(py), groundAtPixel(px, py)));
}

void EditorApp::viewAerial(const osg::Vec3d& centre, double width_m) {
    camera_->setAerial(centre, width_m);
    free_view_ = false;
}

void EditorApp::viewFree(const osg::Vec3d& centre, double distance_m, double heading_deg, double pitch_deg) {
    camera_->setFree(centre, distance_m, heading_deg, pitch_deg);
    free_view_ = true;
}

void EditorApp::submit(EditRequest request) { worker_->submit(std::move(request)); }

void EditorApp::beginGesture() {
    ++gestures_open_;
    EditRequest r;
    r.label = "gesture";
    r.run = [levels = options_.drag_preview_levels](EditSession& s) -> Result<PixelWindow> {
        s.beginGesture();
        // The drag's steps keep their lifts and preview their finest levels; endGesture lifts and
        // synthesizes in full once.
        s.setDragPreviewLevels(levels);
        s.deferLifts(true);
        return PixelWindow{};
    };
    submit(std::move(r));
}

void EditorApp::endGesture(bool timed_release) {
    EditRequest r;
    r.label = "gesture";
    if (timed_release) {
        r.input_seq = latency_.noteInput(InputKind::DragRelease, frame_input_s_);
        r.input_kind = static_cast<int>(InputKind::DragRelease);
    }
    r.run = [](EditSession& s) -> Result<PixelWindow> {
        Result<PixelWindow> lifted = s.liftDeferred();
        s.endGesture();
        return lifted;
    };
    r.done = [this](const EditResult&) { gestures_open_ = std::max(0, gestures_open_ - 1); };
    submit(std::move(r));
}

void EditorApp::submitDragStep(InputKind kind, const std::string& label, const std::string& coalesce_key,
                               std::function<Result<PixelWindow>(EditSession&)> run,
                               std::function<void(const EditResult&)> done) {
    EditRequest r;
    r.label = label;
    r.coalesce_key = coalesce_key;
    r.input_seq = latency_.noteInput(kind, frame_input_s_);
    r.input_kind = static_cast<int>(kind);
    r.run = std::move(run);
    r.done = std::move(done);
    submit(std::move(r));
}

void EditorApp::undo() { stepHistory(false); }
void EditorApp::redo() { stepHistory(true); }

void EditorApp::stepHistory(bool forward) {
    EditRequest r;
    r.label = forward ? "redo" : "undo";
    r.refresh_masks = true;  // painting, freezing and pastes may come back or go
    r.run = [forward](EditSession& s) { return forward ? s.redo() : s.undo(); };
    submit(std::move(r));
    setStatus(r.label, false);
}

void EditorApp::save(const std::string& path) {
    auto saved_count = std::make_shared<uint64_t>(0);
    EditRequest r;
    r.label = "save " + path;
    r.run = [path, saved_count](EditSession& s) -> Result<PixelWindow> {
        *saved_count = s.editCount();
        if (Status st = s.save(path); !st) return st;
        return PixelWindow{};
    };
    r.done = [this, path, saved_count](const EditResult& result) {
        if (!result.status) return;  // onResults shows why; the session stays dirty
        user_saved_count_ = *saved_count;
        setStatus("saved " + path, false);
        std::printf("terrasynth_editor: saved %s\n", path.c_str());
        std::fflush(stdout);
    };
    submit(std::move(r));
}

void EditorApp::autosaveTick() {
    // At most once per interval, and in a pause: a save of a 1024^2 extent writes ~30 MB on the edit
    // thread, and an edit submitted meanwhile would wait for it. When input never pauses (a long
    // sculpting run), an edit older than autosave_max_delay_s is saved between two gestures anyway,
    // so a crash loses at most that much work.
    const double now = steadySeconds();
    if (worker_->editCount() == autosaved_count_) {
        unsaved_since_s_ = -1.0;
        return;
    }
    if (unsaved_since_s_ < 0.0) unsaved_since_s_ = now;
    if (gestures_open_ > 0 || autosave_queued_ || tool_dragging_ || !worker_->idle()) return;
    if (now - last_autosave_s_ < options_.autosave_interval_s) return;
    const bool paused = now - last_input_s_ >= options_.autosave_interval_s;
    const bool overdue = now - unsaved_since_s_ >= options_.autosave_max_delay_s;
    if (!paused && !overdue) return;
    autosave_queued_ = true;
    auto saved_count = std::make_shared<uint64_t>(0);
    EditRequest r;
    r.label = "autosave";
    r.run = [path = autosave_path_, saved_count](EditSession& s) -> Result<PixelWindow> {
        *saved_count = s.editCount();
        if (Status st = s.saveIfDirty(path); !st) return st;
        return PixelWindow{};
    };
    r.done = [this, saved_count](const EditResult& result) {
        autosave_queued_ = false;
        last_autosave_s_ = steadySeconds();
        if (!result.status) return;
        autosaved_count_ = *saved_count;
        unsaved_since_s_ = -1.0;  // edits made during the save start the clock again at the next tick
        autosave_ms_.push_back(result.run_ms);
        std::printf("terrasynth_editor: autosaved %s (edit %llu)\n", autosave_path_.c_str(),
                    static_cast<unsigned long long>(autosaved_count_));
        std::fflush(stdout);
    };
    submit(std::move(r));
}

void EditorApp::addLayer(const std::string& name, ToolParams tool) {
    EditLayer layer;
    layer.name = name;
    layer.weights = defaultWeights(tool);  // the paper's defaults for the tool (layers.h)
    layer.tool = std::move(tool);
    EditRequest r;
    r.label = "add " + name;
    r.run = [layer](EditSession& s) { return s.addLayer(layer); };
    r.done = [this](const EditResult& res) {
        if (res.status && view_) selection_.layer = static_cast<int>(view_->layers.layers.size()) - 1;
    };
    submit(std::move(r));
}

void EditorApp::showHoleFillPreviews(int layer, int generation) {
    previews_layer_ = layer;
    previews_generation_ = generation;
    previews_pending_ = false;
    releasePreviewImages();
}

void EditorApp::releasePreviewImages() {
    for (ImTextureID t : preview_images_) host_.releaseImage(t);
    preview_images_.clear();
}

bool EditorApp::ready() const { return worker_->state() == EditWorker::State::Ready && terrain_; }

bool EditorApp::autosaveHoldsTheLastEdit() const {
    return !autosave_queued_ && autosaved_count_ == worker_->editCount() && worker_->idle();
}

std::optional<ImVec4> EditorApp::itemRect(const std::string& id) const {
    const auto it = items_.find(id);
    if (it == items_.end()) return std::nullopt;
    return it->second;
}

void EditorApp::setStatus(const std::string& text, bool error) {
    status_ = text;
    status_error_ = error;
}

bool EditorApp::settled() const {
    return worker_ && worker_->state() == EditWorker::State::Ready && worker_->idle() && terrain_ &&
           terrain_->settled() && !latency_.pending() && gestures_open_ == 0 && !previews_pending_;
}

void EditorApp::addPhaseTiles(const plugin::TerrainStats& now, TileAccounting& tiles) const {
    const plugin::TerrainStats& start = phase_start_stats_;
    tiles.built += now.tiles_built - start.tiles_built;
    tiles.swapped += now.tiles_swapped - start.tiles_swapped;
    tiles.unchanged += now.rebuilds_unchanged - start.rebuilds_unchanged;
    // The node keeps means since start-up; their sums' difference is this phase's.
    const double built_now = static_cast<double>(now.tiles_built), built_start = static_cast<double>(start.tiles_built);
    tiles.build_ms += now.mean_build_ms * built_now - start.mean_build_ms * built_start;
    tiles.heights_ms += now.mean_heights_ms * built_now - start.mean_heights_ms * built_start;
}

void EditorApp::setPhase(const std::string& name) {
    // Tile work is attributed to edits in every phase but "setup" (where the script moves the camera
    // and the view fills in); the script settles before it leaves setup.
    if (terrain_) {
        const plugin::TerrainStats now = terrain_->stats();
        if (phase_ != "setup") addPhaseTiles(now, tiles_);
        phase_start_stats_ = now;
    }
    phase_ = name;
}

void EditorApp::writeStats() {
    EditorStats st;
    st.window_width = host_.width();
    st.window_height = host_.height();
    if (view_) st.extent_width = view_->extent.width, st.extent_height = view_->extent.height;
    st.latency = &latency_;
    st.frames = &frames_;
    st.tiles = tiles_;
    if (terrain_) {
        const plugin::TerrainStats now = terrain_->stats();
        if (phase_ != "setup") addPhaseTiles(now, st.tiles);
        st.mean_tile_build_ms = now.mean_build_ms;
        st.mean_tile_heights_ms = now.mean_heights_ms;
    }
    st.autosave_ms = autosave_ms_;
    st.renderer = renderer_;
    if (Status s = writeFileAtomically(options_.stats, statsJson(st)); !s) {
        std::fprintf(stderr, "terrasynth_editor: %s\n", s.message().c_str());
        if (exit_code_ == kExitOk) exit_code_ = kExitFailed;
    }
}

}  // namespace terrasynth::editor
