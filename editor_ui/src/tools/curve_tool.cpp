// curve: drag to sketch a course with preset widgets at its start, middle and end (Gain et al. 2015
// s3); with a curve selected, a stroke starting on it over-sketches the part between the stroke's
// ends, and a drag on a widget handle moves the widget along the course (one gesture). A click
// selects the course under the pointer.
#include <algorithm>
#include <memory>

#include <imgui.h>

#include "curve_presets.h"
#include "editor_actions.h"
#include "editor_tool.h"
#include "overlay.h"
#include "tool_kit.h"
#include "tool_options.h"

namespace terrasynth::editor {

const char* curvePresetName(CurvePreset preset) {
    switch (preset) {
        case CurvePreset::Ridge: return "ridge";
        case CurvePreset::Valley: return "valley";
        case CurvePreset::Cliff: return "cliff";
    }
    return "?";
}

std::vector<CurveWidget> presetWidgets(const Polyline& course, CurvePreset preset, float height_m, float reach_px,
                                       const EditorActions& editor) {
    std::vector<CurveWidget> out;
    for (double t : {0.0, 0.5, 1.0}) {
        const auto p = pointAtFraction(course, t);
        const float ground = editor.groundAtPixel(p.first, p.second);
        CurveWidget w;
        w.t = t;
        w.left_reach_px = w.right_reach_px = reach_px;
        switch (preset) {
            case CurvePreset::Ridge:  // a crest: the ground falls away on both sides
                w.height_m = ground + height_m;
                w.left_gradient = w.right_gradient = -0.6f;
                break;
            case CurvePreset::Valley:  // a trough: the ground rises on both sides
                w.height_m = ground - height_m;
                w.left_gradient = w.right_gradient = 0.6f;
                break;
            case CurvePreset::Cliff:  // a cliff top: level on the left, a steep drop on the right
                w.height_m = ground + height_m;
                w.left_gradient = 0.0f;
                w.right_gradient = -3.0f;
                break;
        }
        out.push_back(w);
    }
    return out;
}

namespace {
using namespace tools;

class CurveTool : public EditorTool {
public:
    explicit CurveTool(EditorActions& editor)
        : editor_(editor),
          preset_(editor.options().choice(
              "curve.preset", static_cast<int>(CurvePreset::Ridge),
              [] {
                  std::vector<std::string> names;
                  for (int p = 0; p < kCurvePresets; ++p) names.push_back(curvePresetName(static_cast<CurvePreset>(p)));
                  return names;
              },
              "preset")),
          height_m_(editor.options().number("curve.height", 250.0f)),
          reach_px_(editor.options().number("curve.reach", 32.0f)),
          spline_(editor.options().flag("curve.spline", true)) {}

    const char* name() const override { return "curve"; }
    ToolGroup group() const override { return ToolGroup::Synthesis; }

    bool press(const osg::Vec2d& at, int) override {
        mode_ = Mode::Sketch;
        sketch_.press(editor_, at);
        Selection& selection = editor_.selection();
        if (const CurveItem* c = editor_.view().findCurve(selection.curve)) {
            for (size_t i = 0; i < c->curve.widgets.size(); ++i) {
                const auto pos = pointAtFraction(c->curve.course, c->curve.widgets[i].t);
                if (auto s = editor_.screenOfPixel(pos.first, pos.second); s && screenDistance(*s, at) < kHandlePx) {
                    selection.widget = static_cast<int>(i);
                    mode_ = Mode::MoveWidget;
                    editor_.beginGesture();
                    return true;
                }
            }
        }
        return true;
    }

    void drag(const osg::Vec2d& at) override {
        if (mode_ == Mode::Sketch) return sketch_.drag(editor_, at);
        if (auto now = editor_.pickPixel(at.x(), at.y())) moveWidgetTo(now->first, now->second);
        sketch_.track.follow(at);
    }

    void release(const osg::Vec2d&) override {
        if (mode_ == Mode::MoveWidget) editor_.endGesture(/*timed_release=*/true);
        else finishSketch();
        mode_ = Mode::None;
        sketch_.stroke_px.clear();
    }

    void abandon() override {
        if (mode_ == Mode::MoveWidget) editor_.endGesture();
        mode_ = Mode::None;
        sketch_.stroke_px.clear();
    }

    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (active && mode_ == Mode::Sketch) painter.drape(sketch_.stroke_px, false, overlay_colours::kSketch, 2.0f);
    }

    void drawPanel() override {
        ImGui::TextWrapped("Drag to sketch a course; sketch over the selected one to reshape it; drag its widgets along it.");
        for (int p = 0; p < kCurvePresets; ++p) {
            if (p) ImGui::SameLine();
            if (ImGui::RadioButton(curvePresetName(static_cast<CurvePreset>(p)), preset_ == p)) preset_ = p;
        }
        ImGui::DragFloat("height (m)", &height_m_, 5.0f, 0.0f, 3000.0f, "%.0f");
        ImGui::DragFloat("reach (px)", &reach_px_, 1.0f, 2.0f, 256.0f, "%.0f");
        ImGui::Checkbox("spline", &spline_);
    }

private:
    enum class Mode { None, Sketch, MoveWidget };

    void moveWidgetTo(double px, double py) {
        Selection& selection = editor_.selection();
        const CurveItem* c = editor_.view().findCurve(selection.curve);
        if (!c || selection.widget < 0 || selection.widget >= static_cast<int>(c->curve.widgets.size())) return;
        const double t = nearestOnPolyline(c->curve.course, px, py).t;
        const EditId id = selection.curve;
        const int index = selection.widget;
        // Widgets stay sorted by t: the dragged one may change its index.
        editor_.submitDragStep(InputKind::WidgetDrag, "move widget", "widget-drag",
                               [id, index, t](EditSession& s) { return s.moveWidget(id, index, t); },
                               [this, t](const EditResult& res) {
                                   if (!res.status) return;
                                   Selection& selection = editor_.selection();
                                   if (const CurveItem* cur = editor_.view().findCurve(selection.curve))
                                       for (size_t i = 0; i < cur->curve.widgets.size(); ++i)
                                           if (cur->curve.widgets[i].t == t) selection.widget = static_cast<int>(i);
                               });
    }

    // The nearest distance on the screen from (x, y) to the course, as drawn now.
    double screenDistanceToCourse(const Polyline& course, double x, double y) const {
        double best = 1e9;
        for (size_t i = 1; i < course.size(); ++i) {
            auto a = editor_.screenOfPixel(course[i - 1].first, course[i - 1].second);
            auto b = editor_.screenOfPixel(course[i].first, course[i].second);
            if (a && b) best = std::min(best, nearestOnPolyline({{a->x(), a->y()}, {b->x(), b->y()}}, x, y).distance);
        }
        return best;
    }

    void finishSketch() {
        const double screen_length = sketch_.screenLength(editor_);
        const Polyline stroke = decimate(sketch_.stroke_px, kCourseSpacingPx);
        Selection& selection = editor_.selection();
        const SessionView& view = editor_.view();
        if (stroke.size() < 2 || screen_length < kMinStrokeScreenPx) {
            // A click selects the course under the pointer.
            selection.curve = 0;
            selection.widget = -1;
            EditId hit = 0;
            double best = kHandlePx;
            const osg::Vec2d& at = sketch_.track.press_screen;
            for (const CurveItem& c : view.curves)
                if (const double d = screenDistanceToCourse(c.curve.course, at.x(), at.y()); d < best) best = d, hit = c.id;
            if (hit) selection.selectCurve(hit);
            return;
        }
        // Over-sketch the selected course when the stroke starts on it.
        if (const CurveItem* c = view.findCurve(selection.curve)) {
            const auto start = editor_.screenOfPixel(stroke.front().first, stroke.front().second);
            if (start && screenDistanceToCourse(c->curve.course, start->x(), start->y()) < 2.0 * kHandlePx) {
                CurveConstraint next = c->curve;
                next.course = overSketch(c->curve.course, stroke);
                const EditId id = c->id;
                EditRequest r;
                r.label = "over-sketch curve";
                r.run = [id, next](EditSession& s) { return s.setCurve(id, next); };
                editor_.submit(std::move(r));
                return;
            }
        }
        CurveConstraint curve;
        curve.course = stroke;
        curve.spline = spline_;
        curve.widgets = presetWidgets(stroke, static_cast<CurvePreset>(preset_), height_m_, reach_px_, editor_);
        auto id = std::make_shared<EditId>(0);
        EditRequest r;
        r.label = "add curve";
        r.run = [curve, id](EditSession& s) { return s.addCurve(curve, id.get()); };
        r.done = [this, id](const EditResult& res) {
            if (res.status) editor_.selection().selectCurve(*id);
        };
        editor_.submit(std::move(r));
    }

    EditorActions& editor_;
    int& preset_;      // CurvePreset
    float& height_m_;  // the preset's crest (ridge, cliff top) or trough depth
    float& reach_px_;
    bool& spline_;
    Mode mode_ = Mode::None;
    SketchStroke sketch_;
};

}  // namespace

std::unique_ptr<EditorTool> makeCurveTool(EditorActions& editor) { return std::make_unique<CurveTool>(editor); }

}  // namespace terrasynth::editor
