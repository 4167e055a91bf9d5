#include "terrasynth_host/frame_stats_json.h"

namespace terrasynth::host {

nlohmann::json summaryJson(const std::vector<double>& values) {
    const SeriesSummary s = summarize(values);
    return {{"count", s.count}, {"mean", s.mean}, {"median", s.median}, {"p95", s.p95}, {"max", s.max}};
}

nlohmann::json frameTimesJson(const FrameTimeSeries& f) {
    using T = FrameTiming;
    return {{"frame_ms", summaryJson(f.column(&T::frame_ms))},
            {"main_thread_ms", summaryJson(f.mainThread())},
            {"gl_ms", summaryJson(f.gl())},
            {"events_ms", summaryJson(f.column(&T::events_ms))},
            {"app_ms", summaryJson(f.column(&T::app_ms))},
            {"update_ms", summaryJson(f.column(&T::update_ms))},
            {"cull_ms", summaryJson(f.column(&T::cull_ms))},
            {"draw_ms", summaryJson(f.column(&T::draw_ms))},
            {"overlay_ms", summaryJson(f.column(&T::overlay_ms))},
            {"swap_ms", summaryJson(f.column(&T::swap_ms))},
            {"main_cpu_ms", summaryJson(f.column(&T::main_cpu_ms))},
            {"draw_cpu_ms", summaryJson(f.column(&T::draw_cpu_ms))}};
}

}  // namespace terrasynth::host
