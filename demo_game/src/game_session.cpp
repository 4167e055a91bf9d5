// The frame loop: input, exact ground and rings around the aircraft, the simulation (fixed steps
// that wait for exact ground in deterministic runs, wall-clock steps that never wait otherwise), the
// chase camera, prefetching along the predicted path, the HUD, screenshots, hole checks, statistics.
#include "game_session.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <unordered_set>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "hud.h"
#include "run_stats.h"
#include "scene_models.h"
#include "terrain_loader.h"
#include "terrasynth_game/autopilot.h"
#include "terrasynth_game/chase_camera.h"
#include "terrasynth_game/exact_ground.h"
#include "terrasynth_game/flight_model.h"
#include "terrasynth_game/rings.h"
#include "terrasynth_host/hole_check.h"
#include "terrasynth_host/host_window.h"
#include "terrasynth_plugin/plugin_options.h"
#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::game {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::atomic<bool> g_stop_requested{false};
void onStopSignal(int) { g_stop_requested = true; }

const osg::Vec4 kHoleCheckSky(1.0f, 0.0f, 1.0f, 1.0f);  // magenta: no terrain colour is ever this
constexpr double kCruiseSpeed = 300.0, kCruiseHeight = 300.0;
constexpr double kGroundRadius = 3000.0;  // metres of exact ground kept around the aircraft
constexpr double kRingsShown = 25000.0;   // metres around the aircraft whose rings are drawn
constexpr double kSafeHeight = 100.0;     // above ground: where the aircraft may respawn
constexpr int kMaxSettleFrames = 3000;    // before a deterministic screenshot

// Everything that exists once the terrain is open.
struct World {
    std::shared_ptr<Terrain> terrain;
    HeightSource source;
    double mpp = 0.0;
    osg::ref_ptr<plugin::TerrainNode> node;
    std::unique_ptr<GroundCache> ground;
    std::unique_ptr<RingField> rings;
    std::unique_ptr<RingNodes> ring_nodes;
    osg::ref_ptr<osg::MatrixTransform> aircraft_xf;
    osg::ref_ptr<osg::Group> root;
};

class Session {
public:
    Session(const GameOptions& o, Project project, Clock::time_point start)
        : o_(o), project_(std::move(project)), process_start_(start) {}
    int run();

private:
    bool openWindow();
    bool loadWorld();
    bool makeWorld(std::shared_ptr<Terrain> terrain);
    void placeAtStart();
    bool waitForStartGround();
    bool flightFrame();
    void handleEvents();
    Controls pilotControls() const;
    std::vector<BlockKey> wantGroundAndRings();
    bool groundReadyFor(const std::vector<std::pair<double, double>>& points) const;
    void step(double dt);
    void respawn(const std::string& why);
    std::optional<double> cameraGround(double x, double y) const;
    void applyCamera(const CameraPose& pose);
    void prefetchAhead();
    void buildHud(double frame_ms);
    void measureHeightAt();
    bool settle(int max_frames);
    bool waitForStartView();
    void checkHoles(osg::Image& image);
    void sampleSeries(const plugin::TerrainStats& ts);
    void replayCameraPath();
    void finish();
    void say(const std::string& text) {
        message_ = text;
        message_until_ = sim_time_ + 3.0;
    }

    GameOptions o_;
    Project project_;
    Clock::time_point process_start_;
    RunStats stats_;
    double next_sample_s_ = -1.0;  // wall time of the next series sample (RunStats::series)
    std::unique_ptr<host::HostWindow> host_;
    std::unique_ptr<TerrainLoader> loader_;
    std::optional<std::pair<float, float>> start_heights_;  // level-5 heights around the start
    World world_;
    AutopilotSettings autopilot_settings_;
    std::unique_ptr<Autopilot> autopilot_;  // null: the player flies
    Aircraft aircraft_, safe_point_;
    double safe_point_time_ = -1e9;
    std::unordered_set<uint64_t> collected_;
    bool hud_visible_ = true, quit_ = false;
    double sim_time_ = 0.0, smoothed_frame_ms_ = 0.0;
    Clock::time_point last_frame_ = Clock::now();
    std::string message_;
    double message_until_ = 0.0;
    std::vector<CameraPose> camera_path_;
    int frame_index_ = 0;
    int exit_code_ = 0;
};

// --- start-up ----------------------------------------------------------------------------------

bool Session::openWindow() {
    host::HostOptions ho;
    ho.width = o_.width;
    ho.height = o_.height;
    ho.title = "terrasynth_game - seed " + std::to_string(project_.synthesis.seed);
    ho.fovy_deg = 50.0;
    ho.resizable = o_.screenshot_every == 0 && o_.check_holes_every == 0;  // checks need a fixed size
    ho.clear_color = o_.check_holes_every > 0 ? kHoleCheckSky : osg::Vec4(plugin::TerrainLook{}.fog_colour, 1.0f);
    auto created = host::HostWindow::create(ho);
    if (!created) {
        std::fprintf(stderr, "terrasynth_game: %s\n", created.message().c_str());
        exit_code_ = 2;
        return false;
    }
    host_ = std::move(*created);
    return true;
}

bool Session::loadWorld() {
    TerrainOptions options;
    options.synthesizer.backend = o_.backend;
    // On the loader's thread, behind the progress bar: the heights of the region around the start
    // (level 5, 190 km across with the shipped exemplars) for the look's tints, which also pays the
    // first kernel compile.
    auto after_open = [this](Terrain& t) {
        const double mpp0 = t.metersPerPixel(0), mpp5 = t.metersPerPixel(5);
        const PixelWindow e = t.extent();
        const double sx = o_.start_given ? o_.start_x_km * 1000.0 : (e.x + 0.5 * e.width) * mpp0;
        const double sy = o_.start_given ? o_.start_y_km * 1000.0 : -(e.y + 0.5 * e.height) * mpp0;
        const auto around = t.heights({std::llround(sx / mpp5) - 32, std::llround(-sy / mpp5) - 32, 65, 65}, 5);
        if (around) {
            const auto [lo, hi] = std::minmax_element(around->heights.begin(), around->heights.end());
            start_heights_ = std::make_pair(*lo, *hi);
        }
    };
    loader_ = std::make_unique<TerrainLoader>(project_, options, after_open);
    const auto t0 = Clock::now();
    while (!loader_->done()) {
        const bool open = host_->beginFrame() && !g_stop_requested;
        drawLoading(loader_->stage(), loader_->progress(), secondsSince(t0));
        host_->endFrame();
        if (!open) return false;  // closed while loading; the loader is joined on the way out
    }
    auto result = loader_->result();
    if (!result) {
        std::fprintf(stderr, "terrasynth_game: %s\n", result.message().c_str());
        exit_code_ = 2;
        return false;
    }
    stats_.terrain_ready_s = secondsSince(process_start_);
    return makeWorld(*result);
}

bool Session::makeWorld(std::shared_ptr<Terrain> terrain) {
    World& w = world_;
    w.terrain = terrain;
    w.source = [terrain](const PixelWindow& win, int level) { return terrain->heights(win, level); };
    w.mpp = terrain->metersPerPixel(0);
    stats_.seed = terrain->project().synthesis.seed;
    stats_.device = o_.backend == SynthesisBackend::OpenCL ? "opencl" : "reference";

    plugin::PluginOptions po = *plugin::parsePluginOptions(gameTerrainOptions(o_));  // checked before the window
    // The terrain is read-only here: tiles and the ground cache's blocks (64-quad windows, as the
    // tiles) are cut from one synthesis of their group (height_source.h).
    w.source = plugin::tileGroupedSource(std::move(w.source), po.node.tile_size);
    if (!po.max_level_given) po.node.max_level = plugin::clampedMaxLevel(po.node, terrain->database().levelCount());
    w.node = new plugin::TerrainNode(w.source, w.mpp, po.node);
    // Each tile worker's synthesizer now rather than during the first frames, as the osgDB reader
    // does (reader_writer_tsyn.cpp: one still being made while the window closed corrupted the heap).
    if (Status s = w.node->runOnEveryWorker([&] { return terrain->prepareThisThread(); }); !s) {
        std::fprintf(stderr, "terrasynth_game: %s\n", s.message().c_str());
        exit_code_ = 2;
        return false;
    }
    plugin::TerrainLook look = start_heights_ ? plugin::lookForHeightRange(start_heights_->first, start_heights_->second)
                                              : plugin::TerrainLook{};
    look.fog_visibility_m = static_cast<float>(0.9 * w.node->options().view_radius_m);
    if (po.fog_m) look.fog_visibility_m = *po.fog_m;
    if (po.snow_line_m) look.snow_line_m = *po.snow_line_m;
    if (po.sun_azimuth_deg) look.sun_azimuth_deg = *po.sun_azimuth_deg;
    if (po.sun_elevation_deg) look.sun_elevation_deg = *po.sun_elevation_deg;
    w.node->setLook(look);

    w.ground = std::make_unique<GroundCache>(w.source, w.mpp);
    w.rings = std::make_unique<RingField>(w.source, w.mpp, stats_.seed);
    w.ring_nodes = std::make_unique<RingNodes>();
    w.aircraft_xf = new osg::MatrixTransform;
    w.aircraft_xf->addChild(makeAircraftModel(plugin::sunDirection(look)));
    w.root = new osg::Group;
    w.root->addChild(w.node.get());
    w.root->addChild(w.ring_nodes->root());
    w.root->addChild(w.aircraft_xf.get());
    osgViewer::Viewer& viewer = host_->viewer();
    viewer.setSceneData(w.root.get());
    // The aircraft is 55 m from the eye and the horizon 200 km away: let the near plane follow the
    // scene down to 1/100000 of the far one.
    viewer.getCamera()->setNearFarRatio(1e-5);
    placeAtStart();
    return waitForStartGround();
}

void Session::placeAtStart() {
    const PixelWindow e = world_.terrain->extent();
    aircraft_ = Aircraft{};
    aircraft_.x = o_.start_given ? o_.start_x_km * 1000.0 : (e.x + 0.5 * e.width) * world_.mpp;
    aircraft_.y = o_.start_given ? o_.start_y_km * 1000.0 : -(e.y + 0.5 * e.height) * world_.mpp;
    aircraft_.heading = o_.heading_deg * M_PI / 180.0;
    aircraft_.speed = kCruiseSpeed;
    const double top = FlightParams{}.top_speed;
    aircraft_.throttle = (kCruiseSpeed / top) * (kCruiseSpeed / top);  // level cruise at 300 m/s
    autopilot_settings_.heading_rad = aircraft_.heading;
    autopilot_settings_.horizontal_speed = kCruiseSpeed;
    autopilot_settings_.height_above_ground = kCruiseHeight;
    if (o_.autopilot_s > 0.0) autopilot_ = std::make_unique<Autopilot>(autopilot_settings_);
}

// The aircraft starts 300 m above the exact ground: show the loading screen until it is known.
bool Session::waitForStartGround() {
    const auto t0 = Clock::now();
    while (true) {
        wantGroundAndRings();
        if (const auto g = world_.ground->sample(aircraft_.x, aircraft_.y)) {
            aircraft_.z = g->height_m + kCruiseHeight;
            safe_point_ = aircraft_;
            return waitForStartView();
        }
        const bool open = host_->beginFrame() && !g_stop_requested;
        drawLoading("finding the ground under the start", 1.0, secondsSince(t0));
        host_->endFrame();
        if (!open) return false;
        const GroundCache::Stats gs = world_.ground->stats();
        if (gs.failed > 0) {
            std::fprintf(stderr, "terrasynth_game: %s\n", gs.last_error.c_str());
            exit_code_ = 2;
            return false;
        }
    }
}

// The loading screen stays until every tile the first view wants is drawn: the flight never opens
// on a half-built world with the sky showing through it (the coarse tiles over the whole view
// radius take a few seconds on two cores). Bounded, like settle(): a view that never settles
// starts anyway.
bool Session::waitForStartView() {
    const auto t0 = Clock::now();
    for (int f = 0; f < kMaxSettleFrames; ++f) {
        const plugin::TerrainStats ts = world_.node->stats();
        if (f > 2 && world_.node->settled()) return true;
        const bool open = host_->beginFrame() && !g_stop_requested;
        applyCamera(chaseCamera(aircraft_, [this](double x, double y) { return cameraGround(x, y); }));
        const double wanted = static_cast<double>(std::max<size_t>(1, ts.wanted_tiles));
        drawLoading("building the terrain in view", std::min(1.0, static_cast<double>(ts.drawn_tiles) / wanted),
                    secondsSince(t0));
        host_->endFrame();
        if (!open) return false;
    }
    return true;
}

// --- the frame loop ----------------------------------------------------------------------------

void Session::handleEvents() {
    for (const host::InputEvent& e : host_->routedEvents()) {
        if (e.type != host::InputEvent::Type::KeyDown) continue;
        switch (e.key) {
            case GLFW_KEY_ESCAPE: quit_ = true; break;
            case GLFW_KEY_F1: hud_visible_ = !hud_visible_; break;
            case GLFW_KEY_R: respawn("respawned at the last safe point"); break;
            case GLFW_KEY_P:
                if (autopilot_) {
                    autopilot_.reset();
                    say("autopilot off");
                } else {
                    autopilot_settings_.heading_rad = aircraft_.heading;
                    autopilot_ = std::make_unique<Autopilot>(autopilot_settings_);
                    say("autopilot on");
                }
                break;
            default: break;
        }
    }
}

Controls Session::pilotControls() const {
    auto axis = [this](int plus, int minus) { return (host_->keyDown(plus) ? 1.0 : 0.0) - (host_->keyDown(minus) ? 1.0 : 0.0); };
    Controls c;
    c.pitch = axis(GLFW_KEY_S, GLFW_KEY_W);
    c.roll = axis(GLFW_KEY_D, GLFW_KEY_A);
    c.yaw = axis(GLFW_KEY_E, GLFW_KEY_Q);
    c.throttle = (host_->keyDown(GLFW_KEY_LEFT_SHIFT) || host_->keyDown(GLFW_KEY_RIGHT_SHIFT) ? 1.0 : 0.0) -
                 (host_->keyDown(GLFW_KEY_LEFT_CONTROL) || host_->keyDown(GLFW_KEY_RIGHT_CONTROL) ? 1.0 : 0.0);
    return c;
}

// Exact ground around the aircraft, under the autopilot's (or the predicted) path and under the
// chase camera, then the ring blocks; returns the ring blocks.
std::vector<BlockKey> Session::wantGroundAndRings() {
    GroundCache& ground = *world_.ground;
    std::vector<BlockKey> keys = ground.blocksAround(0, aircraft_.x, aircraft_.y, kGroundRadius);
    auto add = [&keys](const std::vector<BlockKey>& more) {
        for (const BlockKey& k : more)
            if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    };
    double vx, vy, vz;
    aircraft_.velocity(&vx, &vy, &vz);
    for (double t : {5.0, 10.0, 15.0}) add(ground.blocksAround(0, aircraft_.x + vx * t, aircraft_.y + vy * t, 1000.0));
    if (autopilot_)
        for (const auto& [x, y] : autopilot_->lookaheadPoints(aircraft_)) add(ground.blocksAround(0, x, y, 200.0));
    const std::vector<BlockKey> ring_blocks = world_.rings->blocksAround(ground, aircraft_.x, aircraft_.y);
    add(ring_blocks);
    ground.want(std::move(keys));
    world_.rings->update(ground, ring_blocks);
    return ring_blocks;
}

bool Session::groundReadyFor(const std::vector<std::pair<double, double>>& points) const {
    for (const auto& [x, y] : points)
        if (!world_.ground->sample(x, y)) return false;
    return true;
}

void Session::respawn(const std::string& why) {
    aircraft_ = safe_point_;
    aircraft_.speed = std::max(aircraft_.speed, 150.0);
    aircraft_.pitch = 0.0;
    aircraft_.roll = 0.0;
    aircraft_.on_ground = false;
    say(why);
}

void Session::step(double dt) {
    const GroundQuery ground = [g = world_.ground.get()](double x, double y) { return g->sample(x, y); };
    const double x0 = aircraft_.x, y0 = aircraft_.y, z0 = aircraft_.z;
    StepOutcome outcome;
    std::optional<Guidance> guidance = autopilot_ ? autopilot_->decide(aircraft_, ground) : std::nullopt;
    if (autopilot_) {
        if (!guidance) {  // real time and the ground ahead not cached yet: hold the height
            guidance = Guidance{};
            guidance->heading = autopilot_settings_.heading_rad;
            guidance->horizontal_speed = autopilot_settings_.horizontal_speed;
            guidance->vertical_speed = 0.0;
        }
        outcome = stepGuided(aircraft_, *guidance, dt, ground);
    } else {
        outcome = stepAircraft(aircraft_, pilotControls(), dt, ground);
    }
    sim_time_ += dt;
    ++stats_.steps;
    stats_.simulated_s = sim_time_;
    stats_.distance_m += std::hypot(aircraft_.x - x0, aircraft_.y - y0);
    if (outcome == StepOutcome::Crashed) {
        ++stats_.crashes;
        respawn("crashed: respawned at the last safe point");
    }
    // Rings crossed on the way.
    for (const Ring& r : world_.rings->ringsNear(aircraft_.x, aircraft_.y, 1000.0 + aircraft_.speed * dt))
        if (!collected_.count(r.id) && passesThrough(r, x0, y0, z0, aircraft_.x, aircraft_.y, aircraft_.z)) {
            collected_.insert(r.id);
            ++stats_.rings_collected;
            say("ring " + std::to_string(stats_.rings_collected) + "!");
        }
    const std::optional<GroundSample> g = world_.ground->sample(aircraft_.x, aircraft_.y);
    const double ground_m = g ? g->height_m : std::nan("");
    const double agl = aircraft_.z - ground_m;
    if (g) {
        stats_.min_above_ground_m = std::min(stats_.min_above_ground_m, agl);
        stats_.max_above_ground_m = std::max(stats_.max_above_ground_m, agl);
        if (aircraft_.z < ground_m) ++stats_.below_ground_steps;
        if (agl > kSafeHeight && !aircraft_.on_ground && sim_time_ - safe_point_time_ > 1.0) {
            safe_point_ = aircraft_;
            safe_point_time_ = sim_time_;
        }
    }
    stats_.log.push_back({sim_time_, aircraft_.x, aircraft_.y, aircraft_.z, ground_m, agl});
}

std::optional<double> Session::cameraGround(double x, double y) const {
    if (const auto g = world_.ground->sample(x, y)) return g->height_m;
    if (const auto h = world_.node->heightAt(x, y)) return static_cast<double>(*h);
    return std::nullopt;
}

void Session::applyCamera(const CameraPose& pose) {
    host_->viewer().getCamera()->setViewMatrixAsLookAt(pose.eye, pose.center, pose.up);
}

// Tiles the camera will want a few seconds from now, for every level, around the predicted eye.
void Session::prefetchAhead() {
    plugin::TerrainNode& node = *world_.node;
    double vx, vy, vz;
    aircraft_.velocity(&vx, &vy, &vz);
    for (double t : {4.0, 8.0}) {
        const double px = (aircraft_.x + vx * t) / world_.mpp, py = -(aircraft_.y + vy * t) / world_.mpp;
        for (int level = node.options().min_level; level < node.options().max_level; ++level) {
            // Tiles of `level` are drawn within this distance; the square around it covers them.
            const double r = std::min(node.refinementDistance(level), 0.5 * node.options().view_radius_m) / world_.mpp;
            if (r <= 0.0) continue;
            const int side = static_cast<int>(std::min(2.0 * r, 1e9));
            node.prefetch({static_cast<int64_t>(std::floor(px - r)), static_cast<int64_t>(std::floor(py - r)), side, side},
                          level);
        }
    }
}

void Session::buildHud(double frame_ms) {
    HudData d;
    d.speed_ms = aircraft_.speed;
    d.altitude_m = aircraft_.z;
    if (const auto g = world_.ground->sample(aircraft_.x, aircraft_.y)) {
        d.above_ground_m = aircraft_.z - g->height_m;
        d.ground_exact = d.ground_known = true;
    } else if (const auto h = world_.node->heightAt(aircraft_.x, aircraft_.y)) {
        d.above_ground_m = aircraft_.z - *h;
        d.ground_known = true;
    }
    d.x_km = aircraft_.x / 1000.0;
    d.y_km = aircraft_.y / 1000.0;
    d.seed = stats_.seed;
    const plugin::TerrainStats ts = world_.node->stats();
    d.resident_tiles = ts.resident_tiles;
    d.pending_tiles = ts.pending_builds + ts.waiting_merge;
    d.drawn_triangles = ts.drawn_triangles;
    d.frame_ms = frame_ms;
    d.throttle = aircraft_.throttle;
    d.autopilot = autopilot_ != nullptr;
    d.rings_collected = stats_.rings_collected;
    double best = 1e18;
    for (const Ring& r : world_.rings->ringsNear(aircraft_.x, aircraft_.y, kRingsShown)) {
        if (collected_.count(r.id)) continue;
        const double dx = r.x - aircraft_.x, dy = r.y - aircraft_.y, dist = std::hypot(dx, dy);
        const double bearing = std::remainder(std::atan2(dx, dy) - aircraft_.heading, 2.0 * M_PI) * 180.0 / M_PI;
        if (std::fabs(bearing) < 90.0 && dist < best) {
            best = dist;
            d.ring_ahead = true;
            d.ring_distance_m = dist;
            d.ring_bearing_deg = bearing;
        }
    }
    if (sim_time_ < message_until_) d.message = message_;
    drawHud(d);
}

// TerrainNode::heightAt at the aircraft: its cost, and its error against the exact ground where a
// full-resolution (level-0) tile answered.
void Session::measureHeightAt() {
    int level = -1;
    const auto t0 = Clock::now();
    const std::optional<float> h = world_.node->heightAt(aircraft_.x, aircraft_.y, &level);
    stats_.height_at_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    const auto exact = world_.ground->sample(aircraft_.x, aircraft_.y);
    if (h && exact && level == 0) {
        ++stats_.height_at_level0_samples;
        stats_.height_at_level0_max_error_m = std::max(stats_.height_at_level0_max_error_m, std::fabs(*h - exact->height_m));
    }
}

void Session::checkHoles(osg::Image& image) {
    const plugin::TerrainStats ts = world_.node->stats();
    if (ts.drawn_tiles == 0) return;
    const host::HoleCount c = host::countHoles(image, *host_->viewer().getCamera(), ts.drawn_min_height - 1.0,
                                               0.9 * world_.node->options().view_radius_m, kHoleCheckSky);
    ++stats_.hole_frames_checked;
    stats_.hole_pixels += c.holes;
    stats_.hole_required_pixels += c.required;
    if (c.holes > 0) ++stats_.hole_frames_with_holes;
}

// Frames without simulating until every tile the view wants is drawn and the exact ground and
// rings around the aircraft are in: what a deterministic screenshot waits for.
bool Session::settle(int max_frames) {
    for (int f = 0; f < max_frames; ++f) {
        const std::vector<BlockKey> ring_blocks = wantGroundAndRings();
        if (f > 2 && world_.node->settled() && world_.ground->idle() && world_.rings->ready(ring_blocks)) return true;
        if (!host_->beginFrame() || g_stop_requested) {
            host_->endFrame();
            quit_ = true;
            return false;
        }
        applyCamera(chaseCamera(aircraft_, [this](double x, double y) { return cameraGround(x, y); }));
        world_.ring_nodes->sync(world_.rings->ringsNear(aircraft_.x, aircraft_.y, kRingsShown), collected_);
        host_->endFrame(sim_time_);
    }
    return false;
}

// One frame of flight. Returns false when the game should end.
bool Session::flightFrame() {
    const bool open = host_->beginFrame();
    if (!open || g_stop_requested) quit_ = true;
    handleEvents();
    const std::vector<BlockKey> ring_blocks = wantGroundAndRings();

    // Simulate. A deterministic run steps only with the exact ground and rings it needs in hand
    // (the frame is drawn either way); a real-time run never waits.
    const auto now = Clock::now();
    const double wall_dt = std::min(0.1, std::chrono::duration<double>(now - last_frame_).count());
    last_frame_ = now;
    bool stepped = false;
    if (o_.deterministic()) {
        std::vector<std::pair<double, double>> needed{{aircraft_.x, aircraft_.y}};
        if (autopilot_) needed = autopilot_->lookaheadPoints(aircraft_);
        stepped = groundReadyFor(needed) && world_.rings->ready(ring_blocks);
        if (stepped) step(o_.fixed_dt_s);
        else ++stats_.waiting_frames;
    } else if (!quit_) {
        step(wall_dt);
        stepped = true;
    }
    const CameraPose pose = chaseCamera(aircraft_, [this](double x, double y) { return cameraGround(x, y); });
    applyCamera(pose);
    camera_path_.push_back(pose);
    world_.aircraft_xf->setMatrix(aircraftPose(aircraft_));
    world_.ring_nodes->sync(world_.rings->ringsNear(aircraft_.x, aircraft_.y, kRingsShown), collected_);
    prefetchAhead();
    measureHeightAt();
    if (hud_visible_) buildHud(smoothed_frame_ms_);

    ++frame_index_;
    // Real-time runs count frames; deterministic ones count simulation steps, so the same flight
    // takes its screenshots at the same moments however long it waited for the ground.
    const bool screenshot_due = o_.screenshot_every > 0 && (o_.deterministic()
                                    ? stepped && stats_.steps % o_.screenshot_every == 0
                                    : frame_index_ % o_.screenshot_every == 0);
    osg::ref_ptr<osg::Image> capture;
    if (o_.check_holes_every > 0 && frame_index_ % o_.check_holes_every == 0) {
        capture = new osg::Image;
        host_->requestCapture(capture.get(), false);
    }
    if (screenshot_due && !o_.deterministic()) {
        char name[64];
        std::snprintf(name, sizeof name, "/frame_%06d.png", frame_index_);
        host_->requestScreenshot(o_.out_dir + name, true);
    }
    const host::FrameTiming t = host_->endFrame(o_.deterministic() ? sim_time_ : -1.0);
    smoothed_frame_ms_ = smoothed_frame_ms_ == 0.0 ? t.frame_ms : 0.9 * smoothed_frame_ms_ + 0.1 * t.frame_ms;
    const plugin::TerrainStats ts = world_.node->stats();
    if (stats_.first_frame_s < 0.0 && ts.drawn_tiles > 0) stats_.first_frame_s = secondsSince(process_start_);
    stats_.frames.add(t);
    stats_.merge_ms.push_back(ts.last_merge_ms);
    stats_.triangles.push_back(static_cast<double>(ts.drawn_triangles));
    stats_.max_resident_tiles = std::max(stats_.max_resident_tiles, ts.resident_tiles);
    stats_.max_resident_bytes = std::max(stats_.max_resident_bytes, ts.resident_bytes);
    stats_.max_rss_mb = std::max(stats_.max_rss_mb, residentMb());
    sampleSeries(ts);
    if (capture) checkHoles(*capture);
    if (screenshot_due && !o_.deterministic()) {
        ++stats_.screenshots;
        if (!host_->lastScreenshotStatus()) stats_.screenshot_error = host_->lastScreenshotStatus().message();
    }
    // Deterministic screenshots: named by simulation step, of the settled 3D view (no HUD).
    if (screenshot_due && o_.deterministic() && !quit_) {
        settle(kMaxSettleFrames);
        char name[64];
        std::snprintf(name, sizeof name, "/step_%06d.png", stats_.steps);
        host_->requestScreenshot(o_.out_dir + name, false);
        if (host_->beginFrame()) {
            applyCamera(pose);
            host_->endFrame(sim_time_);
            ++stats_.screenshots;
            if (!host_->lastScreenshotStatus()) stats_.screenshot_error = host_->lastScreenshotStatus().message();
        } else {
            host_->endFrame(sim_time_);
            quit_ = true;
        }
    }
    if (o_.autopilot_s > 0.0 && sim_time_ >= o_.autopilot_s) quit_ = true;
    return !quit_;
}

// The flight's camera path again, each pose drawn once every tile it wants is resident and merged:
// what the same frames cost with no streaming, collision or HUD.
void Session::replayCameraPath() {
    world_.aircraft_xf->setMatrix(aircraftPose(aircraft_));
    for (const CameraPose& pose : camera_path_) {
        for (int f = 0; f < kMaxSettleFrames; ++f) {
            if (!host_->beginFrame() || g_stop_requested) {
                host_->endFrame();
                return;
            }
            applyCamera(pose);
            host_->endFrame();
            if (f > 1 && world_.node->settled()) break;
        }
        if (!host_->beginFrame()) {
            host_->endFrame();
            return;
        }
        applyCamera(pose);
        stats_.replay.add(host_->endFrame());
        stats_.replay_triangles.push_back(static_cast<double>(world_.node->stats().drawn_triangles));
    }
}

void Session::sampleSeries(const plugin::TerrainStats& ts) {
    const double now = secondsSince(process_start_);
    if (next_sample_s_ < 0.0) {  // the first flight frame: the interval starts here
        next_sample_s_ = now + RunStats::kSeriesEvery;
        stats_.series_first_frame = stats_.frames.frames().size() - 1;
        stats_.tiles_cap_mb = world_.node->options().cache_mb;
        if (world_.ground) stats_.ground_cap_blocks = world_.ground->maxBlocks();
        return;
    }
    if (now < next_sample_s_) return;
    next_sample_s_ += RunStats::kSeriesEvery;
    const std::vector<double> all = stats_.frames.column(&host::FrameTiming::frame_ms);
    const host::SeriesSummary interval =
        host::summarize(std::vector<double>(all.begin() + static_cast<long>(stats_.series_first_frame), all.end()));
    stats_.series_first_frame = all.size();
    RunStats::Sample x;
    x.t_s = now;
    x.frames = interval.count;
    x.frame_ms_median = interval.median, x.frame_ms_p95 = interval.p95;
    x.rss_mb = residentMb();
    x.tiles_resident = ts.resident_tiles, x.tiles_resident_bytes = ts.resident_bytes;
    x.ground_blocks = world_.ground ? world_.ground->stats().cached : 0;
    stats_.series.push_back(x);
}

void Session::finish() {
    if (world_.node) stats_.terrain = world_.node->stats();
    if (world_.ground) {
        const GroundCache::Stats g = world_.ground->stats();
        stats_.ground_blocks_fetched = g.fetched;
        stats_.ground_fetch_ms_mean = g.mean_fetch_ms;
        stats_.ground_fetch_ms_max = g.max_fetch_ms;
    }
    if (world_.rings) stats_.rings_placed = world_.rings->ringCount();
    // Workers stop here: the scene (tile pool) first, then the ground and ring workers, the loader.
    if (host_) host_->viewer().setSceneData(nullptr);
    world_.root = nullptr;
    world_.aircraft_xf = nullptr;
    world_.ring_nodes.reset();
    world_.node = nullptr;
    world_.rings.reset();
    world_.ground.reset();
    loader_.reset();
    host_.reset();
    stats_.clean_exit = true;
}

int Session::run() {
    std::signal(SIGINT, onStopSignal);
    std::signal(SIGTERM, onStopSignal);
    if (openWindow() && loadWorld()) {
        while (flightFrame()) {
        }
        if (o_.replay && !g_stop_requested) replayCameraPath();
    }
    finish();
    if (!o_.stats_path.empty() && exit_code_ == 0) {
        if (Status s = writeStatsJson(o_.stats_path, o_, stats_); !s) {
            std::fprintf(stderr, "terrasynth_game: %s\n", s.message().c_str());
            return 2;
        }
    }
    if (!stats_.screenshot_error.empty()) std::fprintf(stderr, "terrasynth_game: %s\n", stats_.screenshot_error.c_str());
    return exit_code_;
}

}  // namespace

int runGame(const GameOptions& options, Project project, std::chrono::steady_clock::time_point process_start) {
    Session session(options, std::move(project), process_start);
    return session.run();
}

}  // namespace terrasynth::game
