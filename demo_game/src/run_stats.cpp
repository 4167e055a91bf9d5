#include "run_stats.h"

#include <unistd.h>

#include <cstdio>

#include <nlohmann/json.hpp>

#include "terrasynth/heightfield_io.h"
#include "terrasynth_host/frame_stats_json.h"

namespace terrasynth::game {
using nlohmann::json;
using host::summaryJson;

double residentMb() {
    long pages = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

Status writeStatsJson(const std::string& path, const GameOptions& o, const RunStats& s) {
    json j;
    j["seed"] = s.seed;
    j["project"] = o.project_path;
    j["size"] = {o.width, o.height};
    j["synthesizer"] = s.device;
    j["fixed_dt_s"] = o.fixed_dt_s;
    j["autopilot_s"] = o.autopilot_s;
    j["terrain_options"] = o.terrain_options;
    j["terrain_ready_s"] = s.terrain_ready_s;
    j["first_frame_s"] = s.first_frame_s;
    j["frames"] = s.frames.frames().size();
    j["timing"] = host::frameTimesJson(s.frames);
    j["merge_ms"] = summaryJson(s.merge_ms);
    j["triangles"] = summaryJson(s.triangles);
    j["height_at_us"] = summaryJson(s.height_at_us);
    j["height_at_level0"] = {{"samples", s.height_at_level0_samples}, {"max_error_m", s.height_at_level0_max_error_m}};
    j["max_rss_mb"] = s.max_rss_mb;
    j["flight"] = {{"steps", s.steps},
                   {"simulated_s", s.simulated_s},
                   {"distance_km", s.distance_m / 1000.0},
                   {"waiting_frames", s.waiting_frames},
                   {"min_above_ground_m", s.steps ? s.min_above_ground_m : 0.0},
                   {"max_above_ground_m", s.steps ? s.max_above_ground_m : 0.0},
                   {"below_ground_steps", s.below_ground_steps},
                   {"crashes", s.crashes},
                   {"rings_collected", s.rings_collected},
                   {"rings_placed", s.rings_placed}};
    j["holes"] = {{"frames_checked", s.hole_frames_checked},
                  {"frames_with_holes", s.hole_frames_with_holes},
                  {"hole_pixels", s.hole_pixels},
                  {"required_pixels", s.hole_required_pixels}};
    j["screenshots"] = s.screenshots;
    if (!s.screenshot_error.empty()) j["screenshot_error"] = s.screenshot_error;
    const plugin::TerrainStats& t = s.terrain;
    j["tiles"] = {{"built", t.tiles_built},         {"merged", t.tiles_merged},
                  {"evicted", t.tiles_evicted},     {"build_failures", t.build_failures},
                  {"mean_build_ms", t.mean_build_ms}, {"mean_heights_ms", t.mean_heights_ms},
                  {"max_resident", s.max_resident_tiles}, {"max_resident_mb", s.max_resident_bytes / 1048576.0},
                  {"max_merge_ms", t.max_merge_ms}, {"last_error", t.last_error}};
    j["ground"] = {{"blocks_fetched", s.ground_blocks_fetched},
                   {"fetch_ms_mean", s.ground_fetch_ms_mean},
                   {"fetch_ms_max", s.ground_fetch_ms_max}};
    if (!s.replay.frames().empty()) {
        j["replay"] = host::frameTimesJson(s.replay);
        j["replay"]["triangles"] = summaryJson(s.replay_triangles);
        const double flight_p95 = host::summarize(s.frames.column(&host::FrameTiming::frame_ms)).p95;
        const double replay_p95 = host::summarize(s.replay.column(&host::FrameTiming::frame_ms)).p95;
        j["replay"]["flight_over_replay_p95"] = replay_p95 > 0.0 ? flight_p95 / replay_p95 : 0.0;
    }
    j["caps"] = {{"tiles_mb", s.tiles_cap_mb}, {"ground_blocks", s.ground_cap_blocks}};
    j["series_columns"] = {"t_s", "frames", "frame_ms_median", "frame_ms_p95", "rss_mb",
                           "tiles_resident", "tiles_resident_mb", "ground_blocks"};
    json series = json::array();
    for (const RunStats::Sample& x : s.series)
        series.push_back({x.t_s, x.frames, x.frame_ms_median, x.frame_ms_p95, x.rss_mb, x.tiles_resident,
                          x.tiles_resident_bytes / 1048576.0, x.ground_blocks});
    j["series"] = std::move(series);
    j["clean_exit"] = s.clean_exit;
    j["log_columns"] = {"t_s", "x_m", "y_m", "z_m", "ground_m", "above_ground_m"};
    j["log"] = s.log;
    return writeFileAtomically(path, j.dump(1) + "\n");
}

}  // namespace terrasynth::game
