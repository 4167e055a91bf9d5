// EditWorker: the edit thread (opening the session, running requests with latest-wins coalescing,
// handing the terrain its new heights) and what it publishes for the UI.
#include "terrasynth_editor/edit_worker.h"

#include <algorithm>
#include <chrono>
#include <exception>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "terrasynth/incremental.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::editor {

double steadySeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

const PointItem* SessionView::findPoint(EditId id) const {
    for (const PointItem& p : points)
        if (p.id == id) return &p;
    return nullptr;
}
const CurveItem* SessionView::findCurve(EditId id) const {
    for (const CurveItem& c : curves)
        if (c.id == id) return &c;
    return nullptr;
}
const PasteItem* SessionView::findPaste(EditId id) const {
    for (const PasteItem& p : pastes)
        if (p.id == id) return &p;
    return nullptr;
}

namespace {

// The painted-type / frozen overlay as terrain types (terrain_look.h type colours): frozen pixels
// show as kFrozenOverlayType, painted ones as their type id; coarse samples take the pixel at the
// north-west corner of their block.
constexpr uint8_t kUnknownType = 255;

// Runs `body`, turning an exception (out of memory, a library's throw) into an error Status, so the
// edit thread never dies with the session half-edited. The session's edits do not throw; this is the
// last line of defence.
template <class Body>
auto guardedCall(Body&& body, const std::string& what) -> decltype(body()) {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return Status::error(what + ": out of memory");
    } catch (const std::exception& e) {
        return Status::error(what + ": " + e.what());
    } catch (...) {
        return Status::error(what + ": unknown exception");
    }
}

// `paint` (over its own rectangle) copied onto an extent-sized plane where it is painted.
void stampPaint(const TypePaint& paint, const PixelWindow& extent, std::vector<uint8_t>& plane, bool as_flag) {
    const PixelWindow both = intersectWindows({paint.x, paint.y, paint.width, paint.height}, extent);
    for (int64_t y = both.y; y < both.y + both.height; ++y)
        for (int64_t x = both.x; x < both.x + both.width; ++x) {
            const uint8_t v = paint.types[static_cast<size_t>(y - paint.y) * paint.width + static_cast<size_t>(x - paint.x)];
            if (v == TypePaint::kUnpainted || (as_flag && v == 0)) continue;
            plane[static_cast<size_t>(y - extent.y) * extent.width + static_cast<size_t>(x - extent.x)] = as_flag ? 1 : v;
        }
}

}  // namespace

EditWorker::EditWorker(SessionOpener opener) : opener_(std::move(opener)) {
    thread_ = std::thread([this] { threadMain(); });
}

EditWorker::~EditWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        queue_.clear();
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
    // Tiles built from now on carry no overlay (queued builds keep their copy of the source, which
    // holds the masks it reads).
    if (terrain_) terrain_->setTypeSource({});
}

EditWorker::State EditWorker::state() const { return state_.load(); }

std::string EditWorker::openError() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return open_error_;
}

std::pair<std::string, double> EditWorker::progress() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return {progress_stage_, progress_};
}

void EditWorker::attachTerrain(osg::ref_ptr<plugin::TerrainNode> terrain) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        terrain_ = terrain;
    }
    terrain->setTypeSource([box = mask_box_](const PixelWindow& w, int level) -> Result<std::vector<uint8_t>> {
        std::vector<uint8_t> out(static_cast<size_t>(w.width) * w.height, kUnknownType);
        const std::shared_ptr<const OverlayMasks> m = box->get();
        if (!m) return out;
        const PixelWindow& e = m->extent;
        for (int y = 0; y < w.height; ++y) {
            const int64_t gy = (w.y + y) * (int64_t{1} << level);
            if (gy < e.y || gy >= e.y + e.height) continue;
            for (int x = 0; x < w.width; ++x) {
                const int64_t gx = (w.x + x) * (int64_t{1} << level);
                if (gx < e.x || gx >= e.x + e.width) continue;
                const size_t i = static_cast<size_t>(gy - e.y) * e.width + static_cast<size_t>(gx - e.x);
                if (m->frozen[i]) out[static_cast<size_t>(y) * w.width + x] = plugin::TerrainLook::kTypeColours - 1;
                else if (m->painted[i] != TypePaint::kUnpainted) out[static_cast<size_t>(y) * w.width + x] = m->painted[i];
            }
        }
        return out;
    });
}

void EditWorker::submit(EditRequest request) {
    const double now = steadySeconds();
    EditRequest replaced;  // destroyed after the lock
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_) return;
        if (!request.coalesce_key.empty() && !queue_.empty() &&
            queue_.back().request.coalesce_key == request.coalesce_key) {
            // Latest wins: the newer drag position replaces the one not started yet. The replaced
            // request's wait counts from its submission (that input has waited as long).
            Queued& tail = queue_.back();
            const double submitted = tail.submitted_s;
            const int superseded = tail.superseded + 1;
            replaced = std::move(tail.request);
            tail.request = std::move(request);
            tail.submitted_s = submitted;
            tail.superseded = superseded;
        } else {
            queue_.push_back({std::move(request), now, 0});
        }
    }
    wake_.notify_one();
}

std::vector<EditResult> EditWorker::takeResults(const std::function<void()>& before_done) {
    std::vector<EditResult> out;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        out.swap(results_);
    }
    // Each result was pushed after its view was published (runOne), so view() is at least as new.
    if (before_done) before_done();
    for (const EditResult& r : out)
        if (r.done) r.done(r);
    return out;
}

std::shared_ptr<const SessionView> EditWorker::view() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return view_;
}

std::shared_ptr<const OverlayMasks> EditWorker::masks() const { return mask_box_->get(); }

bool EditWorker::idle() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return queue_.empty() && !running_ && state_.load() != State::Opening;
}

std::pair<std::string, double> EditWorker::running() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!running_) return {"", 0.0};
    return {running_label_, steadySeconds() - running_since_s_};
}

bool EditWorker::waitIdle(double timeout_s) {
    std::unique_lock<std::mutex> lock(mutex_);
    return idle_cv_.wait_for(lock, std::chrono::duration<double>(timeout_s), [this] {
        return queue_.empty() && !running_ && state_.load() != State::Opening;
    });
}

HeightSource EditWorker::heightSource() const {
    TERRASYNTH_REQUIRE(state_.load() == State::Ready, "the session is not open");
    return session_->heightSource();
}

Status EditWorker::prepareThisThread() const {
    TERRASYNTH_REQUIRE(state_.load() == State::Ready, "the session is not open");
    return session_->prepareThisThread();
}

uint64_t EditWorker::editCount() const {
    TERRASYNTH_REQUIRE(state_.load() == State::Ready, "the session is not open");
    return session_->editCount();
}

void EditWorker::threadMain() {
    // At the frame loop's level, above the plugin's tile workers (which run niced). Threads created
    // from here (the OpenCL runtime's, when the session opens) inherit it; Linux nice is per thread.
    // Below the frame loop (nice 5, before), a software rasterizer (llvmpipe) took the cores from
    // the synthesis: on the 2-core machine the point drag's p95 latency was 326-343 ms against
    // 159-194 ms at the same level, for frames a third slower while dragging (median 46-48 against
    // 31-36 ms); the main thread's own work stays small either way (docs/editor.md). With a GPU the
    // draw leaves the cores to the edit.
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kEditThreadNice);
    auto progress = [this](const std::string& stage, double p) {
        std::lock_guard<std::mutex> lock(mutex_);
        progress_stage_ = stage;
        progress_ = p;
    };
    Result<std::unique_ptr<EditSession>> opened =
        guardedCall([&] { return opener_(progress); }, "opening the project");
    if (!opened) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            open_error_ = opened.message();
            queue_.clear();
        }
        state_ = State::Failed;
        idle_cv_.notify_all();
        return;
    }
    session_ = std::move(opened.value());
    refreshMasks();
    publishView();
    state_ = State::Ready;
    idle_cv_.notify_all();

    for (;;) {
        Queued q;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
            if (stop_) break;
            q = std::move(queue_.front());
            queue_.pop_front();
            running_ = true;
            running_label_ = q.request.label;
            running_since_s_ = steadySeconds();
        }
        runOne(q);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            running_ = false;
        }
        idle_cv_.notify_all();
    }
}

void EditWorker::runOne(Queued& q) {
    EditRequest& request = q.request;
    EditResult result;
    result.label = request.label;
    result.input_seq = request.input_seq;
    result.input_kind = request.input_kind;
    result.superseded = q.superseded;
    result.done = std::move(request.done);
    const double start = steadySeconds();
    result.queued_ms = 1e3 * (start - q.submitted_s);
    Result<PixelWindow> changed = guardedCall([&] { return request.run(*session_); }, request.label);
    result.run_ms = 1e3 * (steadySeconds() - start);
    if (!changed) {
        result.status = changed.status();
    } else {
        result.changed = *changed;
        // Painting, freezing, pastes (and undo or redo of them) change what the overlay shows even
        // where no height changed (a freeze changes none).
        const PixelWindow overlay = request.refresh_masks ? refreshMasks() : PixelWindow{};
        result.invalidated = uniteWindows(result.changed, overlay);
        osg::ref_ptr<plugin::TerrainNode> terrain;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            terrain = terrain_;
        }
        if (terrain && !result.invalidated.empty()) {
            // Source first, then the invalidation (see the top of edit_worker.h). The changed window
            // is exact (where level-0 heights differ) and tiles read their apron and coarse blocks
            // through it, so no margin is needed.
            const uint64_t marked_before = terrain->stats().tiles_invalidated;
            terrain->setHeightSource(session_->heightSource());
            result.generation = terrain->invalidate(result.invalidated, 0);
            result.tiles_marked = terrain->stats().tiles_invalidated - marked_before;
            result.tiles_drawn = terrain->drawnTiles().size();
        }
    }
    publishView();
    result.finished_at_s = steadySeconds();
    std::lock_guard<std::mutex> lock(mutex_);
    results_.push_back(std::move(result));
}

PixelWindow EditWorker::refreshMasks() {
    const EditSession& s = *session_;
    auto next = std::make_shared<OverlayMasks>();
    const PixelWindow e = s.extent();
    next->extent = e;
    const size_t n = static_cast<size_t>(e.width) * e.height;
    next->painted.assign(n, TypePaint::kUnpainted);
    next->frozen.assign(n, 0);
    const SynthesisConstraints& c = s.constraints();
    if (!c.types.empty()) stampPaint(c.types, e, next->painted, false);
    if (!c.freeze.empty()) stampPaint(c.freeze, e, next->frozen, true);
    for (const PasteConstraint& p : c.pastes) {
        const std::vector<uint8_t> target = pasteTargetMask(p, e);
        for (size_t i = 0; i < n && i < target.size(); ++i) next->frozen[i] |= target[i] ? 1 : 0;
    }
    std::shared_ptr<const OverlayMasks> previous = masks();
    PixelWindow changed = {e.x, e.y, 0, 0};
    if (previous) {
        changed = uniteWindows(differingWindow(e, previous->painted, next->painted),
                               differingWindow(e, previous->frozen, next->frozen));
    }
    std::lock_guard<std::mutex> lock(mask_box_->mutex);
    mask_box_->masks = std::move(next);
    return changed;
}

void EditWorker::publishView() {
    const EditSession& s = *session_;
    auto built = std::make_shared<SessionView>();
    SessionView* v = built.get();
    v->edit_count = s.editCount();
    v->can_undo = s.canUndo();
    v->can_redo = s.canRedo();
    v->dirty = s.isDirty();
    v->undo_bytes = s.undoBytes();
    v->project_path = s.project().path;
    v->extent = s.extent();
    v->frame = s.frame();
    const HeightRange range = heightRange(s.heights());
    v->min_height_m = range.min;
    v->max_height_m = range.max;
    for (EditId id : s.pointIds()) v->points.push_back({id, *s.point(id)});
    for (EditId id : s.curveIds()) v->curves.push_back({id, *s.curve(id)});
    for (EditId id : s.pasteIds()) v->pastes.push_back({id, *s.paste(id)});
    v->layers = s.layers();
    v->warnings = s.warnings();
    v->database = s.databasePtr();
    v->coarsest_synthesized_level = coarsestSynthesizedLevel(*v->database, s.project().synthesis);
    std::shared_ptr<const SessionView> previous = std::move(built);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        view_.swap(previous);
    }
    // The old view is released here, after the lock: the UI thread's submit() must not wait for
    // its destruction.
}

}  // namespace terrasynth::editor
