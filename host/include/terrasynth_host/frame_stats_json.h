// terrasynth_host/frame_stats_json.h: frame timings as JSON, for the `--stats out.json` reports of
// the editor and the game (one layout, so scripts read both alike).
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "terrasynth_host/frame_stats.h"

namespace terrasynth::host {

// {"count", "mean", "median", "p95", "max"} of `values` (milliseconds or whatever they are).
nlohmann::json summaryJson(const std::vector<double>& values);

// One summary per FrameTiming component: frame_ms, main_thread_ms, gl_ms, events_ms, app_ms,
// update_ms, cull_ms, draw_ms, overlay_ms, swap_ms, main_cpu_ms, draw_cpu_ms.
nlohmann::json frameTimesJson(const FrameTimeSeries& frames);

}  // namespace terrasynth::host
