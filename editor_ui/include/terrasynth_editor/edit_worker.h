// terrasynth_editor/edit_worker.h: the editor's one edit thread.
//
// The UI thread never synthesizes. It submits EditRequests; one worker thread opens the
// EditSession (edit_session.h), runs the requests in order against it, and after every edit that
// changed heights hands the TerrainNode the session's new heightSource() and then invalidates the
// changed level-0 window (in that order: a tile build planned in between reads the new source with
// the old generation and is dropped as stale, never the reverse). Drags submit one request per
// mouse event with a coalescing key: a queued request with the same key at the tail of the queue is
// replaced by the newer one (latest wins), so a slow edit never builds up a backlog and the terrain
// follows the pointer.
//
// The session's accessors are for the edit thread only, so after each request the worker publishes
// a SessionView (copies of the lists, the layer stack, undo state) and, when painting, freezing or
// pastes may have changed, the overlay masks that the terrain's type colours show.
//
// Threading: submit(), takeResults(), view(), masks(), state() and the queries are for any thread;
// the request closures run on the edit thread and may use the session freely.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <osg/ref_ptr>

#include "terrasynth/edit_session.h"
#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::editor {

struct PointItem {
    EditId id = 0;
    PointConstraint point;
};
struct CurveItem {
    EditId id = 0;
    CurveConstraint curve;
};
struct PasteItem {
    EditId id = 0;
    PasteConstraint paste;
};

// What the UI knows of the session after the last request (a copy made on the edit thread).
struct SessionView {
    uint64_t edit_count = 0;
    bool can_undo = false, can_redo = false, dirty = false;
    size_t undo_bytes = 0;
    std::string project_path;  // the file the session belongs to (after an autosave: the autosave)
    PixelWindow extent;
    GridFrame frame;
    float min_height_m = 0.0f, max_height_m = 0.0f;  // of the extent's final heights
    std::vector<PointItem> points;
    std::vector<CurveItem> curves;
    std::vector<PasteItem> pastes;
    LayerStack layers;
    std::vector<std::string> warnings;
    std::shared_ptr<const ExemplarDatabase> database;  // immutable, safe on any thread
    int coarsest_synthesized_level = 0;                // coarser levels are block averages of it

    const PointItem* findPoint(EditId id) const;
    const CurveItem* findCurve(EditId id) const;
    const PasteItem* findPaste(EditId id) const;
};

// Per extent pixel (row-major, extent-sized): the painted type id (TypePaint::kUnpainted where none)
// and whether it is frozen (freeze brush or a paste target).
struct OverlayMasks {
    PixelWindow extent;
    std::vector<uint8_t> painted;
    std::vector<uint8_t> frozen;
};

struct EditRequest {
    std::string label;  // what the status line calls it ("move point")
    // Non-empty: latest wins against a queued request with the same key at the tail of the queue.
    std::string coalesce_key;
    // Runs on the edit thread; returns the level-0 window whose heights changed (empty: none) or an
    // error after which the session must be unchanged (every EditSession edit guarantees that).
    std::function<Result<PixelWindow>(EditSession&)> run;
    // Painting, freezing or pastes may change: recompute the overlay masks afterwards.
    bool refresh_masks = false;
    // Input bookkeeping for latency (latency.h): the newest input this request answers.
    uint64_t input_seq = 0;
    int input_kind = -1;
    // Called on the UI thread by takeResults() with the request's result (optional).
    std::function<void(const struct EditResult&)> done;
};

struct EditResult {
    std::string label;
    Status status = Status::ok();
    PixelWindow changed;      // level-0 heights that changed
    PixelWindow invalidated;  // what the terrain was told to rebuild (changed + overlay changes)
    uint64_t generation = 0;  // TerrainNode::invalidate's generation, 0 when nothing was invalidated
    // Resident tiles in view (drawn, or kept above and around them) that the invalidation marked for
    // a rebuild (TerrainStats::tiles_invalidated; tiles still waiting from an earlier edit count again).
    size_t tiles_marked = 0;
    size_t tiles_drawn = 0;   // tiles the last cull drew, at the same moment
    uint64_t input_seq = 0;
    int input_kind = -1;
    int superseded = 0;       // queued requests this one replaced
    double queued_ms = 0.0;   // from the first submission it replaced to its start
    double run_ms = 0.0;      // the session call
    double finished_at_s = 0.0;  // steady clock, seconds
    std::function<void(const EditResult&)> done;
};

// Opens the session on the edit thread (the database may be built there: progress() reports it).
using SessionOpener = std::function<Result<std::unique_ptr<EditSession>>(
    const std::function<void(const std::string& stage, double progress)>& progress)>;

class EditWorker {
public:
    enum class State { Opening, Ready, Failed };
    // CPU niceness of the edit thread and the OpenCL threads it starts (see threadMain).
    static constexpr int kEditThreadNice = 0;

    // Starts the edit thread, which first runs `opener`.
    explicit EditWorker(SessionOpener opener);
    // Finishes the request being run, drops the rest, joins the thread.
    ~EditWorker();
    EditWorker(const EditWorker&) = delete;
    EditWorker& operator=(const EditWorker&) = delete;

    State state() const;
    // Why opening failed (Failed), "" otherwise.
    std::string openError() const;
    // Opening progress: the stage and [0, 1] (database build), for a progress bar.
    std::pair<std::string, double> progress() const;

    // The terrain that shows the session: gets the height source and invalidations from now on.
    // The overlay type source (masks()) is installed on it.
    void attachTerrain(osg::ref_ptr<plugin::TerrainNode> terrain);
    // Queues a request (Ready only; before that requests wait until the session is open).
    void submit(EditRequest request);
    // Results finished since the last call, oldest first; their `done` callbacks have run, after
    // `before_done` (may be empty): the caller's chance to pick up view(), which already holds what
    // those results did, so the callbacks see it (a new layer is in the view its callback selects).
    std::vector<EditResult> takeResults(const std::function<void()>& before_done = {});

    std::shared_ptr<const SessionView> view() const;  // null until open
    std::shared_ptr<const OverlayMasks> masks() const;
    // Nothing queued and nothing running.
    bool idle() const;
    // Label of the request running now and for how long (seconds), or "" when none.
    std::pair<std::string, double> running() const;
    // Blocks until idle (tests, scripts). False on timeout.
    bool waitIdle(double timeout_s);
    // The session's heightSource(), prepareThisThread(), editCount() and isDirty() (thread-safe in
    // the session); the session must be open.
    HeightSource heightSource() const;
    Status prepareThisThread() const;
    uint64_t editCount() const;

private:
    struct Queued {
        EditRequest request;
        double submitted_s = 0.0;
        int superseded = 0;
    };
    void threadMain();
    void runOne(Queued& q);
    void publishView();
    PixelWindow refreshMasks();  // returns the box of what changed

    SessionOpener opener_;
    std::unique_ptr<EditSession> session_;  // the edit thread's (set once open)
    std::atomic<State> state_{State::Opening};

    mutable std::mutex mutex_;  // everything below
    std::condition_variable wake_, idle_cv_;
    std::deque<Queued> queue_;
    std::vector<EditResult> results_;
    bool stop_ = false;
    bool running_ = false;
    std::string running_label_;
    double running_since_s_ = 0.0;
    std::string open_error_;
    std::string progress_stage_ = "opening";
    double progress_ = 0.0;
    std::shared_ptr<const SessionView> view_;
    // The current masks, shared with the terrain's type source: tile builds may still read it after
    // this worker is gone (they hold copies of the source).
    struct MaskBox {
        mutable std::mutex mutex;
        std::shared_ptr<const OverlayMasks> masks;
        std::shared_ptr<const OverlayMasks> get() const {
            std::lock_guard<std::mutex> lock(mutex);
            return masks;
        }
    };
    std::shared_ptr<MaskBox> mask_box_ = std::make_shared<MaskBox>();
    osg::ref_ptr<plugin::TerrainNode> terrain_;

    std::thread thread_;  // last: started once everything above exists
};

// Seconds on the steady clock (the time base of EditResult and latency.h).
double steadySeconds();

}  // namespace terrasynth::editor
