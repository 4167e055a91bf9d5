// The panels: menu bar, tools, inspector (points, curves, pastes), status bar, opening and recovery
// screens. ImGui only: no GL here (the host draws), no session access (requests go to the worker).
#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "editor_app.h"
#include "tools/curve_presets.h"

namespace terrasynth::editor {
namespace {

constexpr float kLeftWidth = 270.0f, kStatusHeight = 26.0f;
constexpr ImGuiWindowFlags kPanelFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;

}  // namespace

void EditorApp::noteItem(const std::string& id) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    items_[id] = ImVec4(a.x, a.y, b.x, b.y);
}

void EditorApp::trackGesture(const std::string& id) {
    if (ImGui::IsItemActivated() && !active_gestures_[id]) {
        active_gestures_[id] = true;
        beginGesture();
    }
    if (ImGui::IsItemDeactivated() && active_gestures_[id]) {
        active_gestures_[id] = false;
        endGesture();
    }
}

float& EditorApp::liveValue(const std::string& key, float current) {
    // While an item is being dragged it edits its own copy: the session's view lags behind by the
    // edit's time, and restarting from it every frame would stall the drag.
    float& slot = live_values_[key];
    if (!active_gestures_[key]) slot = current;
    return slot;
}

void EditorApp::drawPanels() {
    drawMenuBar();
    drawToolPanel();
    drawInspector();
    drawLayersPanel();
    drawExemplarsPanel();
    drawHoleFillPreviews();
    drawStatusBar();
}

void EditorApp::drawMenuBar() {
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Save", "Ctrl+S")) save(save_path_);
        if (ImGui::MenuItem("Quit")) host_.requestClose();
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        if (ImGui::MenuItem("Undo", "Ctrl+Z", false, view_ && view_->can_undo)) undo();
        if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, view_ && view_->can_redo)) redo();
        if (ImGui::MenuItem("Delete selection", "Del")) deleteSelection();
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        if (ImGui::MenuItem("Free 3D view", nullptr, free_view_) && camera_)
            viewFree(camera_->center(), std::max(camera_->distance(), 1000.0), 0.0, 40.0);
        if (ImGui::MenuItem("Aerial view", nullptr, !free_view_) && camera_) viewAerial(camera_->center(), camera_->viewWidthM());
        ImGui::Separator();
        ImGui::MenuItem("Constraints' reach", nullptr, show_reach_);
        if (ImGui::MenuItem("Painted types and frozen areas", nullptr, &show_types_) && terrain_) {
            plugin::TerrainLook look = terrain_->look();
            look.type_colour_mix = show_types_ ? 0.5f : 0.0f;
            terrain_->setLook(look);
        }
        ImGui::EndMenu();
    }
    ImGui::EndMainMenuBar();
}

void EditorApp::drawToolPanel() {
    const float top = ImGui::GetFrameHeight();
    ImGui::SetNextWindowPos(ImVec2(0, top), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kLeftWidth, 0.5f * (host_.height() - top - kStatusHeight)), ImGuiCond_Always);
    ImGui::Begin("Tools", nullptr, kPanelFlags);
    ImGui::TextDisabled("Synthesis (Gain et al. 2015)");
    int column = 0;
    ToolGroup group = ToolGroup::Synthesis;
    for (const auto& tool : tools_) {
        if (tool->group() != group) {
            group = tool->group();
            ImGui::NewLine();
            ImGui::TextDisabled("Layers (Bradbury et al. 2014)");
            column = 0;
        }
        if (column++ % 3) ImGui::SameLine();
        if (ImGui::RadioButton(tool->name(), tool_ == tool.get())) selectTool(tool->name());
        noteItem(std::string("tool.") + tool->name());
    }
    ImGui::Separator();
    tool_->drawPanel();
    ImGui::End();
}

void EditorApp::drawInspector() {
    const float top = ImGui::GetFrameHeight();
    const float h = 0.5f * (host_.height() - top - kStatusHeight);
    ImGui::SetNextWindowPos(ImVec2(0, top + h), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kLeftWidth, h), ImGuiCond_Always);
    ImGui::Begin("Inspector", nullptr, kPanelFlags);
    if (const PointItem* p = view_->findPoint(selection_.point)) drawPointInspector(*p);
    else if (const CurveItem* c = view_->findCurve(selection_.curve)) drawCurveInspector(*c);
    else if (const PasteItem* q = view_->findPaste(selection_.paste)) drawPasteInspector(*q);
    else {
        ImGui::TextDisabled("Nothing selected");
        ImGui::Text("%zu points, %zu curves, %zu pastes", view_->points.size(), view_->curves.size(), view_->pastes.size());
    }
    ImGui::End();
}

void EditorApp::drawPointInspector(const PointItem& item) {
    ImGui::Text("Point %" PRIu64 " at (%.0f, %.0f)", item.id, item.point.x - view_->extent.x, item.point.y - view_->extent.y);
    PointConstraint p = item.point;
    const std::string k = "point." + std::to_string(item.id) + ".";
    bool changed = false;
    auto field = [&](const char* label, const char* key, float* value, float speed, float lo, float hi, const char* format) {
        float& live = liveValue(k + key, *value);
        changed |= ImGui::DragFloat(label, &live, speed, lo, hi, format);
        trackGesture(k + key);
        noteItem(std::string("point.") + key);
        *value = live;
    };
    field("height (m)", "height", &p.height_m, 5.0f, -12000.0f, 12000.0f, "%.0f");
    field("slope dir (deg)", "slope_dir", &p.slope_direction_deg, 1.0f, 0.0f, 360.0f, "%.0f");
    field("slope (deg)", "slope", &p.slope_angle_deg, 0.5f, 0.0f, 80.0f, "%.1f");
    field("radius (px)", "radius", &p.radius_px, 1.0f, 1.0f, 2048.0f, "%.0f");
    if (changed) {
        const EditId id = item.id;
        EditRequest r;
        r.label = "set point";
        r.coalesce_key = "point-set";
        r.run = [id, p](EditSession& s) { return s.setPoint(id, p); };
        submit(std::move(r));
    }
    if (ImGui::Button("Remove point")) deleteSelection();
}

void EditorApp::drawCurveInspector(const CurveItem& item) {
    ImGui::Text("Curve %" PRIu64 ": %zu course points", item.id, item.curve.course.size());
    const EditId id = item.id;
    auto setCurve = [&](const CurveConstraint& next, const char* label) {
        EditRequest r;
        r.label = label;
        r.coalesce_key = "curve-set";
        r.run = [id, next](EditSession& s) { return s.setCurve(id, next); };
        submit(std::move(r));
    };
    bool spline = item.curve.spline;
    if (ImGui::Checkbox("spline", &spline)) {
        CurveConstraint next = item.curve;
        next.spline = spline;
        setCurve(next, "spline toggle");
    }
    ImGui::Text("Preset:");
    for (int p = 0; p < kCurvePresets; ++p) {
        ImGui::SameLine();
        if (ImGui::SmallButton(curvePresetName(static_cast<CurvePreset>(p)))) {
            CurveConstraint next = item.curve;
            std::vector<CurveWidget> preset = presetWidgets(item.curve.course, static_cast<CurvePreset>(p),
                                                            tool_options_.number("curve.height"),
                                                            tool_options_.number("curve.reach"), *this);
            next.widgets.clear();
            for (const CurveWidget& old : item.curve.widgets) {
                // The preset's shape at each existing widget's place.
                const auto at = pointAtFraction(item.curve.course, old.t);
                CurveWidget w = preset[0];
                w.t = old.t;
                w.height_m = preset[0].height_m - groundAtPixel(pointAtFraction(item.curve.course, 0.0).first,
                                                                pointAtFraction(item.curve.course, 0.0).second) +
                             groundAtPixel(at.first, at.second);
                next.widgets.push_back(w);
            }
            setCurve(next, "curve preset");
        }
    }
    if (ImGui::Button("Add widget")) {
        CurveWidget w = item.curve.widgets.empty() ? CurveWidget{} : item.curve.widgets.front();
        w.t = 0.25;
        const auto at = pointAtFraction(item.curve.course, w.t);
        w.height_m = groundAtPixel(at.first, at.second) + tool_options_.number("curve.height");
        EditRequest r;
        r.label = "add widget";
        r.run = [id, w](EditSession& s) { return s.addWidget(id, w); };
        submit(std::move(r));
    }
    for (size_t i = 0; i < item.curve.widgets.size(); ++i) {
        ImGui::PushID(static_cast<int>(i));
        CurveWidget w = item.curve.widgets[i];
        const bool open = ImGui::CollapsingHeader(("widget " + std::to_string(i)).c_str(),
                                                  static_cast<int>(i) == selection_.widget ? ImGuiTreeNodeFlags_DefaultOpen : 0);
        if (ImGui::IsItemClicked()) selection_.widget = static_cast<int>(i);
        if (open) {
            bool changed = false;
            const std::string k = "widget." + std::to_string(id) + "." + std::to_string(i) + ".";
            float& t = liveValue(k + "t", static_cast<float>(w.t));
            if (ImGui::SliderFloat("t", &t, 0.0f, 1.0f, "%.3f")) {
                const int index = static_cast<int>(i);
                const double at = t;
                EditRequest r;
                r.label = "move widget";
                r.coalesce_key = "widget-t";
                r.run = [id, index, at](EditSession& s) { return s.moveWidget(id, index, at); };
                submit(std::move(r));
            }
            trackGesture(k + "t");
            auto field = [&](const char* label, const char* key, float* value, float speed, float lo, float hi, const char* format) {
                float& live = liveValue(k + key, *value);
                changed |= ImGui::DragFloat(label, &live, speed, lo, hi, format);
                trackGesture(k + key);
                *value = live;
            };
            field("height (m)", "height", &w.height_m, 5.0f, -12000.0f, 12000.0f, "%.0f");
            field("left gradient", "lg", &w.left_gradient, 0.01f, -10.0f, 10.0f, "%.2f");
            field("right gradient", "rg", &w.right_gradient, 0.01f, -10.0f, 10.0f, "%.2f");
            field("left reach (px)", "lr", &w.left_reach_px, 0.5f, 1.0f, 1000.0f, "%.0f");
            field("right reach (px)", "rr", &w.right_reach_px, 0.5f, 1.0f, 1000.0f, "%.0f");
            if (changed) {
                const int index = static_cast<int>(i);
                EditRequest r;
                r.label = "set widget";
                r.coalesce_key = "widget-set";
                r.run = [id, index, w](EditSession& s) { return s.setWidget(id, index, w); };
                submit(std::move(r));
            }
            if (item.curve.widgets.size() > 1 && ImGui::SmallButton("remove widget")) {
                const int index = static_cast<int>(i);
                EditRequest r;
                r.label = "remove widget";
                r.run = [id, index](EditSession& s) { return s.removeWidget(id, index); };
                submit(std::move(r));
            }
        }
        ImGui::PopID();
    }
    if (ImGui::Button("Remove curve")) {
        selection_.widget = -1;
        deleteSelection();
    }
}

void EditorApp::drawPasteInspector(const PasteItem& item) {
    ImGui::Text("Paste %" PRIu64 " from %s", item.id,
                item.paste.exemplar < 0 ? "the terrain" : view_->database->exemplars[static_cast<size_t>(item.paste.exemplar)].name.c_str());
    // Keyed by the paste's source, not its id: moving a paste gives it a new id mid-drag.
    const std::string k = "paste." + std::to_string(item.paste.source.size()) + ".";
    float& dx = liveValue(k + "dx", static_cast<float>(item.paste.dx));
    float& dy = liveValue(k + "dy", static_cast<float>(item.paste.dy));
    float& raise = liveValue(k + "raise", item.paste.height_offset_m);
    bool changed = ImGui::DragFloat("offset x (px)", &dx, 1.0f, -1e6f, 1e6f, "%.0f");
    trackGesture(k + "dx");
    changed |= ImGui::DragFloat("offset y (px)", &dy, 1.0f, -1e6f, 1e6f, "%.0f");
    trackGesture(k + "dy");
    changed |= ImGui::DragFloat("raise (m)", &raise, 5.0f, -5000.0f, 5000.0f, "%.0f");
    trackGesture(k + "raise");
    noteItem("paste.raise");
    const float offset[2] = {dx, dy};
    if (changed) {
        PasteConstraint next = item.paste;
        next.dx = std::round(offset[0]);
        next.dy = std::round(offset[1]);
        next.height_offset_m = raise;
        const EditId old = item.id;
        auto id = std::make_shared<EditId>(0);
        EditRequest r;
        r.label = "move paste";
        r.coalesce_key = "paste-set";
        r.refresh_masks = true;
        r.run = [old, next, id](EditSession& s) -> Result<PixelWindow> {
            s.beginGesture();
            Result<PixelWindow> removed = s.removePaste(old);
            Result<PixelWindow> added = removed ? s.addPaste(next, id.get()) : removed;
            s.endGesture();
            if (!added) {
                if (removed) s.undo();
                return added.status();
            }
            return uniteWindows(*removed, *added);
        };
        r.done = [this, id](const EditResult& res) {
            if (res.status) selection_.paste = *id;
        };
        submit(std::move(r));
    }
    if (ImGui::Button("Remove paste")) deleteSelection();
}

void EditorApp::drawStatusBar() {
    ImGui::SetNextWindowPos(ImVec2(0, host_.height() - kStatusHeight), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(host_.width()), kStatusHeight), ImGuiCond_Always);
    ImGui::Begin("##status", nullptr, kPanelFlags | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar);
    const auto [running, seconds] = worker_->running();
    if (!running.empty() && seconds > 0.25 && running != "gesture") {
        // Large edits (re-synthesis of a wide area, hole fill) run on the edit thread: show it.
        ImGui::ProgressBar(std::fmod(static_cast<float>(seconds) * 0.5f, 1.0f), ImVec2(120, 0), "");
        ImGui::SameLine();
        ImGui::Text("%s (%.1f s)", running.c_str(), seconds);
        ImGui::SameLine();
    }
    if (status_error_) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", status_.c_str());
    else ImGui::TextUnformatted(status_.c_str());
    char right[256];
    const bool unsaved = view_->edit_count != user_saved_count_;
    std::snprintf(right, sizeof right, "%s | %" PRIu64 " edits%s | undo %.1f MB | %s", save_path_.c_str(),
                  view_->edit_count, unsaved ? " (unsaved)" : "", view_->undo_bytes / 1048576.0, tool_->name());
    ImGui::SameLine(std::max(ImGui::GetWindowWidth() - ImGui::CalcTextSize(right).x - 12.0f, 300.0f));
    ImGui::TextUnformatted(right);
    ImGui::End();
}

void EditorApp::drawOpeningScreen() {
    ImGui::SetNextWindowPos(ImVec2(0.5f * host_.width(), 0.5f * host_.height()), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(460, 0), ImGuiCond_Always);
    ImGui::Begin("Opening", nullptr, kPanelFlags);
    ImGui::TextWrapped("%s", project_.path.c_str());
    if (worker_ && worker_->state() == EditWorker::State::Failed) {
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", worker_->openError().c_str());
        if (ImGui::Button("Quit")) host_.requestClose();
    } else if (worker_) {
        const auto [stage, fraction] = worker_->progress();
        ImGui::Text("%s", stage.c_str());
        ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(-1, 0));
    }
    ImGui::End();
}

void EditorApp::drawRecoverPrompt() {
    ImGui::SetNextWindowPos(ImVec2(0.5f * host_.width(), 0.5f * host_.height()), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(520, 0), ImGuiCond_Always);
    ImGui::Begin("Recover autosave?", nullptr, kPanelFlags);
    ImGui::TextWrapped("%s was written after %s: the last session may have ended without saving.", recover_from_.c_str(),
                       project_.path.c_str());
    if (ImGui::Button("Recover the autosave")) {
        asking_recover_ = false;
        startOpening(recover_from_);
    }
    ImGui::SameLine();
    if (ImGui::Button("Open the project")) {
        asking_recover_ = false;
        recover_from_.clear();
        startOpening(project_.path);
    }
    ImGui::End();
}

}  // namespace terrasynth::editor
