// LatencyTracker and the --stats report.
#include "terrasynth_editor/latency.h"

#include <nlohmann/json.hpp>

#include "terrasynth_editor/edit_worker.h"
#include "terrasynth_host/frame_stats_json.h"

namespace terrasynth::editor {

const char* inputKindName(InputKind kind) {
    switch (kind) {
        case InputKind::PointDrag: return "point_drag";
        case InputKind::BandSlider: return "band_slider";
        case InputKind::WidgetDrag: return "widget_drag";
        case InputKind::DragRelease: return "drag_release";
    }
    return "unknown";
}

uint64_t LatencyTracker::noteInput(InputKind kind, double t_s) {
    const int k = static_cast<int>(kind);
    const uint64_t seq = ++next_seq_[k];
    inputs_[k].push_back({seq, t_s});
    return seq;
}

void LatencyTracker::noteResult(const EditResult& r) {
    if (r.input_kind < 0 || r.input_kind >= kInputKinds || r.input_seq == 0) return;
    const auto kind = static_cast<InputKind>(r.input_kind);
    if (!r.status) {
        // Nothing of these inputs will ever be shown.
        auto& in = inputs_[r.input_kind];
        while (!in.empty() && in.front().seq <= r.input_seq) in.pop_front();
        return;
    }
    applied_.push_back({kind, r.input_seq, r.generation, r.finished_at_s, r.queued_ms, r.run_ms});
}

void LatencyTracker::afterUpdate(const std::function<size_t(uint64_t)>& awaiting, double now_s) {
    // Results resolve in order: a later edit's tiles cannot be on screen before an earlier one's.
    while (!applied_.empty()) {
        const Applied& a = applied_.front();
        if (a.generation != 0 && awaiting(a.generation) != 0) break;
        auto& in = inputs_[static_cast<int>(a.kind)];
        while (!in.empty() && in.front().seq <= a.seq) {
            Swapped s;
            s.kind = static_cast<int>(a.kind);
            s.t_input_s = in.front().t_s;
            s.sample.applied_ms = 1e3 * (a.applied_s - s.t_input_s);
            s.sample.swapped_ms = 1e3 * (now_s - s.t_input_s);
            s.sample.queued_ms = a.queued_ms;
            s.sample.edit_ms = a.edit_ms;
            swapped_.push_back(s);
            in.pop_front();
        }
        applied_.pop_front();
    }
}

void LatencyTracker::afterFrame(double now_s) {
    for (Swapped& s : swapped_) {
        s.sample.shown_ms = 1e3 * (now_s - s.t_input_s);
        done_[s.kind].push_back(s.sample);
    }
    swapped_.clear();
}

bool LatencyTracker::pending() const {
    if (!applied_.empty() || !swapped_.empty()) return true;
    for (const auto& in : inputs_)
        if (!in.empty()) return true;
    return false;
}

void LatencyTracker::clear() {
    for (auto& in : inputs_) in.clear();
    applied_.clear();
    swapped_.clear();
    for (auto& d : done_) d.clear();
}

host::FrameTimeSeries PhasedFrames::of(const std::string& phase) const {
    host::FrameTimeSeries out;
    for (const auto& [p, t] : frames)
        if (p == phase) out.add(t);
    return out;
}

using host::summaryJson;

std::string statsJson(const EditorStats& st) {
    nlohmann::json j;
    j["window"] = {st.window_width, st.window_height};
    j["extent"] = {st.extent_width, st.extent_height};
    j["renderer"] = st.renderer;
    nlohmann::json latency = nlohmann::json::object();
    if (st.latency) {
        for (int k = 0; k < kInputKinds; ++k) {
            const auto& samples = st.latency->samples(static_cast<InputKind>(k));
            std::vector<double> applied, swapped, shown, queued, edit;
            for (const LatencySample& s : samples) {
                applied.push_back(s.applied_ms);
                swapped.push_back(s.swapped_ms);
                shown.push_back(s.shown_ms);
                queued.push_back(s.queued_ms);
                edit.push_back(s.edit_ms);
            }
            latency[inputKindName(static_cast<InputKind>(k))] = {{"event_to_applied_ms", summaryJson(applied)},
                                                                  {"event_to_swapped_ms", summaryJson(swapped)},
                                                                  {"event_to_shown_ms", summaryJson(shown)},
                                                                  {"queued_ms", summaryJson(queued)},
                                                                  {"edit_ms", summaryJson(edit)}};
        }
    }
    j["latency"] = latency;
    nlohmann::json frames = nlohmann::json::object();
    if (st.frames) {
        std::vector<std::string> phases;
        for (const auto& [p, t] : st.frames->frames)
            if (std::find(phases.begin(), phases.end(), p) == phases.end()) phases.push_back(p);
        for (const std::string& p : phases) frames[p] = host::frameTimesJson(st.frames->of(p));
    }
    j["frames"] = frames;
    j["tiles"] = {{"edits", st.tiles.edits},         {"touching_changed_window", st.tiles.touching},
                  {"in_view", st.tiles.in_view},     {"rebuilt", st.tiles.built},
                  {"swapped", st.tiles.swapped},     {"rebuilt_unchanged", st.tiles.unchanged},
                  {"mean_build_ms", st.mean_tile_build_ms}, {"mean_heights_ms", st.mean_tile_heights_ms},
                  {"edit_mean_build_ms", st.tiles.built ? st.tiles.build_ms / st.tiles.built : 0.0},
                  {"edit_mean_heights_ms", st.tiles.built ? st.tiles.heights_ms / st.tiles.built : 0.0}};
    j["autosave_ms"] = summaryJson(st.autosave_ms);
    return j.dump(2) + "\n";
}

}  // namespace terrasynth::editor
