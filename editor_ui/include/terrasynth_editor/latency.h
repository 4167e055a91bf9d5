// terrasynth_editor/latency.h: how long an input takes to reach the screen, and the editor's stats.
//
// Every input event of a measured interaction (a point drag's mouse move, a band slider's change, a
// curve widget's drag) gets a sequence number and the time the editor received it (right after the
// host polled the window). The request answering it carries the newest sequence number it covers
// (latest wins: one request answers every input it replaced). An input is
//   applied  when the edit thread finished the session call that includes it,
//   swapped  at the end of the first UPDATE traversal after which no tile in view still waits for
//            a rebuild from that edit (TerrainNode::tilesAwaitingRebuild): the changed tiles are in
//            the scene graph, not yet drawn,
//   shown    when the frame drawn after that UPDATE has been swapped to the screen.
// Failed edits drop their inputs (nothing to show). Plain bookkeeping: main thread only, no GL.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "terrasynth_host/frame_stats.h"

namespace terrasynth::editor {

struct EditResult;

// DragRelease: the release of a point or widget drag, answered by the gesture's end (the deferred
// lifts and the full synthesis after a preview).
enum class InputKind : int { PointDrag = 0, BandSlider = 1, WidgetDrag = 2, DragRelease = 3 };
constexpr int kInputKinds = 4;
const char* inputKindName(InputKind kind);  // "point_drag", "band_slider", "widget_drag", "drag_release"

struct LatencySample {
    double applied_ms = 0.0, swapped_ms = 0.0, shown_ms = 0.0;  // from the input
    double queued_ms = 0.0, edit_ms = 0.0;  // of the request that answered it
};

class LatencyTracker {
public:
    // A new input of `kind` received at `t_s` (steadySeconds()); returns its sequence number (>= 1).
    uint64_t noteInput(InputKind kind, double t_s);
    // A finished request (any; those without an input kind are ignored).
    void noteResult(const EditResult& result);
    // After the UPDATE traversal: `awaiting(generation)` is TerrainNode::tilesAwaitingRebuild.
    void afterUpdate(const std::function<size_t(uint64_t)>& awaiting, double now_s);
    // After the frame was swapped to the screen.
    void afterFrame(double now_s);
    // Inputs not yet shown.
    bool pending() const;
    const std::vector<LatencySample>& samples(InputKind kind) const { return done_[static_cast<int>(kind)]; }
    void clear();

private:
    struct Input {
        uint64_t seq;
        double t_s;
    };
    struct Applied {
        InputKind kind;
        uint64_t seq;
        uint64_t generation;
        double applied_s, queued_ms, edit_ms;
    };
    struct Swapped {
        int kind;
        LatencySample sample;
        double t_input_s;
    };
    std::array<uint64_t, kInputKinds> next_seq_{};
    std::array<std::deque<Input>, kInputKinds> inputs_;
    std::deque<Applied> applied_;
    std::vector<Swapped> swapped_;
    std::array<std::vector<LatencySample>, kInputKinds> done_;
};

// Frames of a run by phase ("idle", "drag", ...), for the --stats report.
struct PhasedFrames {
    std::vector<std::pair<std::string, host::FrameTiming>> frames;
    void add(const std::string& phase, const host::FrameTiming& t) { frames.emplace_back(phase, t); }
    host::FrameTimeSeries of(const std::string& phase) const;
};

// Tile work attributed to edits: tiles rebuilt (built by workers) while edits were being shown,
// against the tiles in view that touched the edits' invalidated windows.
struct TileAccounting {
    uint64_t edits = 0;
    uint64_t touching = 0;   // sum over edits of the resident tiles in view touching the window
    uint64_t in_view = 0;    // sum over edits of the resident tiles in view
    uint64_t built = 0, swapped = 0, unchanged = 0;  // TerrainStats deltas over the measured phases
    double build_ms = 0.0, heights_ms = 0.0;         // summed over those builds (of which reading heights)
};

// Everything --stats writes, as JSON text (docs/editor.md).
struct EditorStats {
    int window_width = 0, window_height = 0;
    int extent_width = 0, extent_height = 0;
    const LatencyTracker* latency = nullptr;
    const PhasedFrames* frames = nullptr;
    TileAccounting tiles;
    std::vector<double> autosave_ms;
    double mean_tile_build_ms = 0.0;
    double mean_tile_heights_ms = 0.0;  // of mean_tile_build_ms: reading the height source
    std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
};
std::string statsJson(const EditorStats& stats);

}  // namespace terrasynth::editor
