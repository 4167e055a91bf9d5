// terrasynth_host/frame_stats.h: where a frame's time went, and summaries of many frames.
//
// A host frame (HostWindow::beginFrame .. endFrame) is split into the main thread's own work and
// the GL draw, so that what an application adds can be told apart from what the rasterizer costs
// (on Mesa llvmpipe the GL draw is CPU work too, done by llvmpipe's threads while the main thread
// waits in glFinish / swap):
//   main thread: events (poll + ImGui new frame + routing), app (between beginFrame and endFrame:
//                game logic, ImGui widgets), update (osgViewer event + update traversals: tile
//                merges, manipulators), cull
//   GL draw:     draw (OSG draw traversal, then glFinish when HostOptions::finish_gl_for_timing),
//                overlay (ImGui's GL calls), swap
// Plain data; no GL. Summaries are computed by sorting, not estimated.
#pragma once

#include <cstddef>
#include <vector>

namespace terrasynth::host {

struct FrameTiming {  // milliseconds of one frame
    double events_ms = 0.0;
    double app_ms = 0.0;
    double update_ms = 0.0;
    double cull_ms = 0.0;
    double draw_ms = 0.0;
    double overlay_ms = 0.0;
    double screenshot_ms = 0.0;  // reading back (and writing) a screenshot or capture; 0 on most frames
    double swap_ms = 0.0;
    double frame_ms = 0.0;  // beginFrame start to endFrame end
    // CPU time, which other processes on a shared machine do not inflate the way they inflate the
    // wall-clock figures above: the main thread's over the whole frame, and the whole process's
    // (llvmpipe's rasterizer threads included, and any worker running meanwhile) during the draw.
    double main_cpu_ms = 0.0;
    double draw_cpu_ms = 0.0;

    double glMs() const { return draw_ms + overlay_ms + swap_ms; }
    // Everything the main thread does itself: the frame less the GL draw and screenshot I/O.
    double mainThreadMs() const { return frame_ms - glMs() - screenshot_ms; }
};

struct SeriesSummary {
    size_t count = 0;
    double mean = 0.0, median = 0.0, p95 = 0.0, max = 0.0;
};

// Summary of `values` (any order). p95 is the nearest-rank 95th percentile. Empty -> all zero.
SeriesSummary summarize(std::vector<double> values);

// Per-frame timings of a run; one add() per frame.
class FrameTimeSeries {
public:
    void add(const FrameTiming& t) { frames_.push_back(t); }
    void clear() { frames_.clear(); }
    const std::vector<FrameTiming>& frames() const { return frames_; }
    // One component over the frames, e.g. column(&FrameTiming::cull_ms).
    std::vector<double> column(double FrameTiming::*member) const;
    std::vector<double> mainThread() const;
    std::vector<double> gl() const;

private:
    std::vector<FrameTiming> frames_;
};

}  // namespace terrasynth::host
