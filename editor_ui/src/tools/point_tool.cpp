// point: click the terrain to add a point constraint (Gain et al. 2015 s3: the ground's height plus
// a raise, with a slope and a radius), drag a handle to move one. The move is one gesture whose
// steps preview the synthesis and whose release finishes it (docs/editor.md).
#include <cmath>
#include <memory>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "tool_kit.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class PointTool : public EditorTool {
public:
    explicit PointTool(EditorActions& editor)
        : editor_(editor),
          raise_m_(editor.options().number("point.raise", 300.0f)),
          radius_px_(editor.options().number("point.radius", 64.0f)),
          slope_deg_(editor.options().number("point.slope", 0.0f)),
          slope_direction_deg_(editor.options().number("point.slope_dir", 0.0f)) {}

    const char* name() const override { return "point"; }
    ToolGroup group() const override { return ToolGroup::Synthesis; }

    bool press(const osg::Vec2d& at, int) override {
        track_.start(editor_, at);
        const SessionView& view = editor_.view();
        // Grab the nearest handle, else put a new point on the ground.
        EditId hit = 0;
        double best = kHandlePx;
        for (const PointItem& p : view.points)
            if (auto s = editor_.screenOfPixel(p.point.x, p.point.y); s && screenDistance(*s, at) < best)
                best = screenDistance(*s, at), hit = p.id;
        if (hit) {
            // Remember where the point was: it follows the pointer by the distance moved (a handle
            // grabbed off-centre does not jump).
            const PointConstraint& grabbed = view.findPoint(hit)->point;
            grabbed_at_ = {grabbed.x, grabbed.y};
            editor_.selection().selectPoint(hit);
            editor_.beginGesture();
            dragging_ = true;
            return true;
        }
        if (!track_.press_px) {
            editor_.setStatus("no terrain under the pointer", true);
            return false;
        }
        PointConstraint p;
        p.x = std::round(track_.press_px->first);
        p.y = std::round(track_.press_px->second);
        p.height_m = editor_.groundAtPixel(p.x, p.y) + raise_m_;
        p.radius_px = radius_px_;
        p.slope_angle_deg = slope_deg_;
        p.slope_direction_deg = slope_direction_deg_;
        auto id = std::make_shared<EditId>(0);
        EditRequest r;
        r.label = "add point";
        r.run = [p, id](EditSession& s) { return s.addPoint(p, id.get()); };
        r.done = [this, id](const EditResult& res) {
            if (res.status) editor_.selection().selectPoint(*id);
        };
        editor_.submit(std::move(r));
        return false;
    }

    void drag(const osg::Vec2d& at) override {
        const auto now = editor_.pickPixel(at.x(), at.y());
        if (!now || !track_.press_px || !track_.moved(at)) return;
        // From the site where the drag started (the view may already show intermediate moves).
        const EditId id = editor_.selection().point;
        const double dx = now->first - track_.press_px->first, dy = now->second - track_.press_px->second;
        const double x = std::round(grabbed_at_.first + dx), y = std::round(grabbed_at_.second + dy);
        editor_.submitDragStep(InputKind::PointDrag, "move point", "point-drag",
                               [id, x, y](EditSession& s) { return s.movePoint(id, x, y); });
        track_.last_screen = at;
    }

    void release(const osg::Vec2d&) override {
        editor_.endGesture(/*timed_release=*/true);
        dragging_ = false;
    }

    void abandon() override {
        if (dragging_) editor_.endGesture();
        dragging_ = false;
    }

    void drawPanel() override {
        ImGui::TextWrapped("Click the terrain to add a point, drag a handle to move it, Del removes it.");
        ImGui::DragFloat("raise (m)", &raise_m_, 5.0f, -3000.0f, 3000.0f, "%.0f");
        ImGui::DragFloat("radius (px)", &radius_px_, 1.0f, 4.0f, 512.0f, "%.0f");
        ImGui::DragFloat("slope (deg)", &slope_deg_, 0.5f, 0.0f, 80.0f, "%.1f");
        ImGui::DragFloat("slope dir (deg)", &slope_direction_deg_, 1.0f, 0.0f, 360.0f, "%.0f");
    }

private:
    EditorActions& editor_;
    float& raise_m_;  // a new point's height above the ground it is put on
    float& radius_px_;
    float& slope_deg_;
    float& slope_direction_deg_;
    DragTrack track_;
    std::pair<double, double> grabbed_at_;  // the grabbed point's site when the drag started
    bool dragging_ = false;
};

}  // namespace

std::unique_ptr<EditorTool> makePointTool(EditorActions& editor) { return std::make_unique<PointTool>(editor); }

}  // namespace terrasynth::editor
