// perspective: in the free view, draw a ridge's silhouette against the sky; its feet are found on
// the ground through the view's perspective and its heights by single-view metrology (Bradbury et
// al. 2014 s4.1, with the 3D view itself as the canvas).
#include <array>
#include <cmath>
#include <memory>

#include <imgui.h>

#include "editor_actions.h"
#include "editor_tool.h"
#include "overlay.h"
#include "tool_kit.h"
#include "tool_options.h"

namespace terrasynth::editor {
namespace {
using namespace tools;

class PerspectiveTool : public EditorTool {
public:
    explicit PerspectiveTool(EditorActions& editor) : editor_(editor), width_px_(editor.options().number("ridge.width", 10.0f)) {}

    const char* name() const override { return "perspective"; }
    ToolGroup group() const override { return ToolGroup::Layers; }

    bool press(const osg::Vec2d& at, int) override {
        stroke_screen_ = {at};
        last_screen_ = at;
        return true;
    }

    void drag(const osg::Vec2d& at) override {
        if (screenDistance(at, last_screen_) < kMovePx) return;
        stroke_screen_.push_back(at);
        last_screen_ = at;
    }

    void release(const osg::Vec2d&) override {
        finishStroke();
        stroke_screen_.clear();
    }

    void abandon() override { stroke_screen_.clear(); }

    void drawOverlay(OverlayPainter& painter, bool active) override {
        if (active && stroke_screen_.size() > 1) painter.screenPolyline(stroke_screen_, overlay_colours::kSketch, 2.5f);
    }

    void drawPanel() override {
        ImGui::TextWrapped("In the 3D view, draw a ridge's silhouette against the sky: its feet and heights come from the view's perspective (s4.1).");
        ImGui::DragFloat("width (px)", &width_px_, 0.5f, 1.0f, 200.0f, "%.0f");
    }

private:
    void finishStroke() {
        const EditorCamera* camera = editor_.camera();
        if (stroke_screen_.size() < 2 || !camera) return;
        const ScreenProjection& projection = editor_.projection();
        const SessionView& view = editor_.view();
        // The perspective canvas (s4.1) over the 3D view itself: the ground plane at the view centre's
        // height, a square of it ahead of the camera as the grid, its vanishing line as the horizon.
        const osg::Vec3d c = camera->center();
        const double h = osg::DegreesToRadians(camera->headingDeg());
        const osg::Vec3d ahead(std::sin(h), std::cos(h), 0.0), right(std::cos(h), -std::sin(h), 0.0);
        const double half = 0.4 * camera->distance();
        const osg::Vec3d corners[4] = {c - ahead * half - right * half, c - ahead * half + right * half,
                                       c + ahead * half + right * half, c + ahead * half - right * half};
        PerspectiveCanvas canvas;
        canvas.image_width = projection.width();
        canvas.image_height = projection.height();
        std::array<Point2, 4> image;
        const GridFrame& f = view.frame;
        for (int i = 0; i < 4; ++i) {
            const auto s = projection.toScreen(corners[i]);
            if (!s) return editor_.setStatus("perspective: tilt the view so the ground ahead is visible", true);
            image[static_cast<size_t>(i)] = {s->x(), s->y()};
            canvas.ground[static_cast<size_t>(i)] = {f.pixelX(corners[i].x()) - view.extent.x, f.pixelY(corners[i].y()) - view.extent.y};
        }
        canvas.grid_near = {image[0], image[1]};
        canvas.grid_right = {image[1], image[2]};
        canvas.grid_far = {image[3], image[2]};
        canvas.grid_left = {image[0], image[3]};
        const auto v1 = projection.toScreen(c + ahead * 1e9), v2 = projection.toScreen(c + (ahead + right) * 1e9);
        if (!v1 || !v2) return editor_.setStatus("perspective: the horizon is behind the camera", true);
        canvas.horizon = {{v1->x(), v1->y()}, {v2->x(), v2->y()}};
        osg::Vec3d eye, dir;
        projection.ray(0.5 * projection.width(), 0.5 * projection.height(), &eye, &dir);
        canvas.camera_height_m = std::max(1.0, eye.z() - c.z());
        SilhouetteStroke stroke;
        for (const osg::Vec2d& p : stroke_screen_) stroke.points.push_back({p.x(), p.y()});
        stroke.width_px = width_px_;
        PerspectiveParams params;
        params.reference_image = "3D view";
        params.canvas = canvas;
        params.strokes = {stroke};
        editor_.addLayer("perspective sketch", params);
    }

    EditorActions& editor_;
    float& width_px_;  // the ridges' width, shared with the ridge tool
    std::vector<osg::Vec2d> stroke_screen_;
    osg::Vec2d last_screen_;
};

}  // namespace

std::unique_ptr<EditorTool> makePerspectiveTool(EditorActions& editor) { return std::make_unique<PerspectiveTool>(editor); }

}  // namespace terrasynth::editor
