// What a run measured, and its --stats JSON (written atomically). Private to the game.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "terrasynth/status.h"
#include "terrasynth_game/game_options.h"
#include "terrasynth_host/frame_stats.h"
#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::game {

struct RunStats {
    uint32_t seed = 0;
    std::string device;             // synthesizer backend
    double terrain_ready_s = -1.0;  // process start to the terrain being open
    double first_frame_s = -1.0;    // process start to the first frame that drew terrain
    // Flight frames (loading, settling and replay frames excluded).
    host::FrameTimeSeries frames;
    std::vector<double> merge_ms, triangles, height_at_us;
    double max_rss_mb = 0.0;
    // The flight.
    int steps = 0, waiting_frames = 0, crashes = 0, rings_collected = 0, below_ground_steps = 0;
    double simulated_s = 0.0, distance_m = 0.0;
    double min_above_ground_m = std::numeric_limits<double>::max(), max_above_ground_m = std::numeric_limits<double>::lowest();
    // TerrainNode::heightAt against the exact ground where a level-0 tile answered.
    int height_at_level0_samples = 0;
    double height_at_level0_max_error_m = 0.0;
    // No-holes check (--check-holes).
    int hole_frames_checked = 0, hole_frames_with_holes = 0;
    long long hole_pixels = 0, hole_required_pixels = 0;
    int screenshots = 0;
    std::string screenshot_error;
    // Per simulation step: t, x, y, z, exact ground, above ground.
    std::vector<std::array<double, 6>> log;
    // --replay: the same camera path, every tile resident.
    host::FrameTimeSeries replay;
    std::vector<double> replay_triangles;
    plugin::TerrainStats terrain;
    size_t max_resident_tiles = 0, max_resident_bytes = 0;
    size_t ground_blocks_fetched = 0;
    double ground_fetch_ms_mean = 0.0, ground_fetch_ms_max = 0.0;
    size_t rings_placed = 0;
    bool clean_exit = false;
    // A sample every kSeriesEvery seconds of wall time from the first flight frame on, for soak
    // runs (scripts/soak_game.sh): how frame times, memory and the caches move over a long flight.
    static constexpr double kSeriesEvery = 10.0;
    struct Sample {
        double t_s = 0.0;  // since the process started
        size_t frames = 0;  // flight frames in the interval
        double frame_ms_median = 0.0, frame_ms_p95 = 0.0;
        double rss_mb = 0.0;
        size_t tiles_resident = 0, tiles_resident_bytes = 0, ground_blocks = 0;
    };
    std::vector<Sample> series;
    size_t series_first_frame = 0;  // first flight frame of the interval being sampled
    double tiles_cap_mb = 0.0;      // the caches' caps, as configured
    size_t ground_cap_blocks = 0;
};

Status writeStatsJson(const std::string& path, const GameOptions& options, const RunStats& stats);

// Resident set size of this process, MiB (from /proc/self/statm).
double residentMb();

}  // namespace terrasynth::game
