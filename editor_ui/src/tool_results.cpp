// The tools' finished interactions: what a sketch, a region, a perspective stroke or a paste becomes
// (curves with preset widgets, over-sketches, layers of Bradbury et al. 2014, pastes of Gain et al.
// 2015 s5.3), each one request to the edit thread.
#include <algorithm>
#include <cmath>

#include "editor_app.h"
#include "tool_helpers.h"

namespace terrasynth::editor {
using namespace tools;

std::vector<CurveWidget> EditorApp::presetWidgets(const Polyline& course) const {
    std::vector<CurveWidget> out;
    for (double t : {0.0, 0.5, 1.0}) {
        const auto p = pointAtFraction(course, t);
        const float ground = groundAtPixel(p.first, p.second);
        CurveWidget w;
        w.t = t;
        w.left_reach_px = w.right_reach_px = tool_options_.curve_reach_px;
        switch (tool_options_.curve_preset) {
            case CurvePreset::Ridge:  // a crest: the ground falls away on both sides
                w.height_m = ground + tool_options_.curve_height_m;
                w.left_gradient = w.right_gradient = -0.6f;
                break;
            case CurvePreset::Valley:  // a trough: the ground rises on both sides
                w.height_m = ground - tool_options_.curve_height_m;
                w.left_gradient = w.right_gradient = 0.6f;
                break;
            case CurvePreset::Cliff:  // a cliff top: level on the left, a steep drop on the right
                w.height_m = ground + tool_options_.curve_height_m;
                w.left_gradient = 0.0f;
                w.right_gradient = -3.0f;
                break;
        }
        out.push_back(w);
    }
    return out;
}

void EditorApp::finishSketch() {
    const double screen_length = [&] {
        double l = 0.0;
        for (size_t i = 1; i < drag_.stroke_px.size(); ++i) {
            auto a = screenOfPixel(drag_.stroke_px[i - 1].first, drag_.stroke_px[i - 1].second);
            auto b = screenOfPixel(drag_.stroke_px[i].first, drag_.stroke_px[i].second);
            if (a && b) l += screenDistance(*a, *b);
        }
        return l;
    }();
    const Polyline stroke = decimate(drag_.stroke_px, kCourseSpacingPx);
    const bool is_click = stroke.size() < 2 || screen_length < kMinStrokeScreenPx;
    if (tool_ == Tool::Ridge) {
        if (is_click) return;
        RidgeParams ridge;
        for (const auto& p : stroke) ridge.points.push_back({p.first - view_->extent.x, p.second - view_->extent.y});
        ridge.profile_m = {tool_options_.ridge_height_m};
        ridge.width_px = tool_options_.ridge_width_px;
        addLayer("ridge", ridge);
        return;
    }
    // Curves: a click selects the course under the pointer.
    if (is_click) {
        selected_curve_ = 0;
        selected_widget_ = -1;
        double best = kHandlePx;
        for (const CurveItem& c : view_->curves)
            for (size_t i = 1; i < c.curve.course.size(); ++i) {
                auto a = screenOfPixel(c.curve.course[i - 1].first, c.curve.course[i - 1].second);
                auto b = screenOfPixel(c.curve.course[i].first, c.curve.course[i].second);
                if (!a || !b) continue;
                const Nearest n = nearestOnPolyline({{a->x(), a->y()}, {b->x(), b->y()}}, drag_.press_screen.x(), drag_.press_screen.y());
                if (n.distance < best) best = n.distance, selected_curve_ = c.id;
            }
        if (selected_curve_) selected_point_ = selected_paste_ = 0;
        return;
    }
    // Over-sketch the selected course when the stroke starts on it.
    if (const CurveItem* c = view_->findCurve(selected_curve_)) {
        const auto start = screenOfPixel(stroke.front().first, stroke.front().second);
        double near_course = 1e9;
        for (size_t i = 1; i < c->curve.course.size() && start; ++i) {
            auto a = screenOfPixel(c->curve.course[i - 1].first, c->curve.course[i - 1].second);
            auto b = screenOfPixel(c->curve.course[i].first, c->curve.course[i].second);
            if (a && b)
                near_course = std::min(near_course, nearestOnPolyline({{a->x(), a->y()}, {b->x(), b->y()}}, start->x(), start->y()).distance);
        }
        if (near_course < 2.0 * kHandlePx) {
            CurveConstraint next = c->curve;
            next.course = overSketch(c->curve.course, stroke);
            const EditId id = c->id;
            EditRequest r;
            r.label = "over-sketch curve";
            r.run = [id, next](EditSession& s) { return s.setCurve(id, next); };
            submit(std::move(r));
            return;
        }
    }
    CurveConstraint curve;
    curve.course = stroke;
    curve.spline = tool_options_.curve_spline;
    curve.widgets = presetWidgets(stroke);
    auto id = std::make_shared<EditId>(0);
    EditRequest r;
    r.label = "add curve";
    r.run = [curve, id](EditSession& s) { return s.addCurve(curve, id.get()); };
    r.done = [this, id](const EditResult& res) {
        if (res.status) selected_curve_ = *id, selected_point_ = selected_paste_ = 0, selected_widget_ = -1;
    };
    submit(std::move(r));
}

void EditorApp::finishRegion() {
    const auto end = pickPixel(drag_.last_screen.x(), drag_.last_screen.y());
    const bool is_click = !end || !drag_.press_px || screenDistance(drag_.last_screen, drag_.press_screen) < kMinStrokeScreenPx;
    const PixelWindow& e = view_->extent;
    ToolParams tool;
    if (tool_ == Tool::Noise) {
        NoiseParams noise;
        noise.fractal.amplitude_m = tool_options_.noise_amplitude_m;
        noise.fractal.wavelength_px = tool_options_.noise_wavelength_px;
        noise.fractal.octaves = 6;
        noise.fractal.seed = view_->edit_count + 1;
        if (!is_click) noise.region = regionBetween(*drag_.press_px, *end, e, RegionShape::Ellipse);
        noise.feather_px = 16.0;
        tool = noise;
    } else if (is_click) {
        if (tool_ == Tool::LayerPaste && layer_paste_source_ && drag_.press_px) {
            // Second step of a layer paste: the copied rectangle lands centred on the click.
            PasteParams paste;
            paste.source_x = layer_paste_source_->x;
            paste.source_y = layer_paste_source_->y;
            paste.dest = *layer_paste_source_;
            paste.dest.shape = RegionShape::Ellipse;
            paste.dest.x = drag_.press_px->first - e.x - 0.5 * paste.dest.width;
            paste.dest.y = drag_.press_px->second - e.y - 0.5 * paste.dest.height;
            paste.feather_px = 8.0;
            tool = paste;
            layer_paste_source_.reset();
        } else {
            return;
        }
    } else if (tool_ == Tool::LayerPaste) {
        layer_paste_source_ = regionBetween(*drag_.press_px, *end, e, RegionShape::Rect);
        setStatus("copied: click where the copy goes", false);
        return;
    } else {  // hole fill
        HoleFillParams fill;
        fill.hole = regionBetween(*drag_.press_px, *end, e, RegionShape::Ellipse);
        fill.seed = view_->edit_count + 1;
        tool = fill;
    }
    const bool hole_fill = std::holds_alternative<HoleFillParams>(tool);
    addLayer(tool_ == Tool::Noise ? "noise" : tool_ == Tool::LayerPaste ? "layer paste" : "hole fill", tool);
    if (hole_fill) {
        // Offer the three variants of the new layer (s4.4) once it exists.
        previews_layer_ = static_cast<int>(view_->layers.layers.size());
        previews_generation_ = 0;
        previews_pending_ = false;
        for (ImTextureID t : preview_images_) host_.releaseImage(t);
        preview_images_.clear();
    }
}

void EditorApp::finishPerspectiveStroke() {
    if (drag_.stroke_screen.size() < 2 || !camera_) return;
    // The perspective canvas (s4.1) over the 3D view itself: the ground plane at the view centre's
    // height, a square of it ahead of the camera as the grid, its vanishing line as the horizon.
    const osg::Vec3d c = camera_->center();
    const double h = osg::DegreesToRadians(camera_->headingDeg());
    const osg::Vec3d ahead(std::sin(h), std::cos(h), 0.0), right(std::cos(h), -std::sin(h), 0.0);
    const double half = 0.4 * camera_->distance();
    const osg::Vec3d corners[4] = {c - ahead * half - right * half, c - ahead * half + right * half,
                                   c + ahead * half + right * half, c + ahead * half - right * half};
    PerspectiveCanvas canvas;
    canvas.image_width = projection_.width();
    canvas.image_height = projection_.height();
    std::array<Point2, 4> image;
    const GridFrame& f = view_->frame;
    for (int i = 0; i < 4; ++i) {
        const auto s = projection_.toScreen(corners[i]);
        if (!s) return setStatus("perspective: tilt the view so the ground ahead is visible", true);
        image[static_cast<size_t>(i)] = {s->x(), s->y()};
        canvas.ground[static_cast<size_t>(i)] = {f.pixelX(corners[i].x()) - view_->extent.x, f.pixelY(corners[i].y()) - view_->extent.y};
    }
    canvas.grid_near = {image[0], image[1]};
    canvas.grid_right = {image[1], image[2]};
    canvas.grid_far = {image[3], image[2]};
    canvas.grid_left = {image[0], image[3]};
    const auto v1 = projection_.toScreen(c + ahead * 1e9), v2 = projection_.toScreen(c + (ahead + right) * 1e9);
    if (!v1 || !v2) return setStatus("perspective: the horizon is behind the camera", true);
    canvas.horizon = {{v1->x(), v1->y()}, {v2->x(), v2->y()}};
    osg::Vec3d eye, dir;
    projection_.ray(0.5 * projection_.width(), 0.5 * projection_.height(), &eye, &dir);
    canvas.camera_height_m = std::max(1.0, eye.z() - c.z());
    SilhouetteStroke stroke;
    for (const osg::Vec2d& p : drag_.stroke_screen) stroke.points.push_back({p.x(), p.y()});
    stroke.width_px = tool_options_.ridge_width_px;
    PerspectiveParams params;
    params.reference_image = "3D view";
    params.canvas = canvas;
    params.strokes = {stroke};
    addLayer("perspective sketch", params);
}

void EditorApp::placePaste(double dx, double dy, std::optional<EditId> replacing) {
    PasteConstraint paste;
    if (replacing) {
        const PasteItem* p = view_->findPaste(*replacing);
        if (!p) return;
        paste = p->paste;
    } else {
        paste.source = paste_source_;
        paste.exemplar = paste_exemplar_;
        paste.height_offset_m = tool_options_.paste_offset_m;
    }
    paste.dx = dx;
    paste.dy = dy;
    auto id = std::make_shared<EditId>(0);
    EditRequest r;
    r.label = replacing ? "move paste" : "paste";
    r.refresh_masks = true;
    r.run = [paste, replacing, id](EditSession& s) -> Result<PixelWindow> {
        if (!replacing) return s.addPaste(paste, id.get());
        // Moving or raising a paste: remove and paste again, one undo step; put it back on failure.
        s.beginGesture();
        Result<PixelWindow> removed = s.removePaste(*replacing);
        Result<PixelWindow> added = removed ? s.addPaste(paste, id.get()) : removed;
        s.endGesture();
        if (!added) {
            if (removed) {
                if (auto back = s.undo(); !back) return back.status().withContext("restoring the paste");
            }
            return added.status();
        }
        return uniteWindows(*removed, *added);
    };
    r.done = [this, id, replacing](const EditResult& res) {
        if (!res.status) return;
        selected_paste_ = *id, selected_point_ = selected_curve_ = 0;
        if (!replacing) {
            // The next lasso starts a new copy.
            paste_source_.clear();
            paste_exemplar_ = -1;
            setStatus("pasted: drag it to move it, raise it in the inspector", false);
        }
    };
    submit(std::move(r));
}

void EditorApp::addLayer(const std::string& name, ToolParams tool) {
    EditLayer layer;
    layer.name = name;
    layer.weights = defaultWeights(tool);  // the paper's defaults for the tool (layers.h)
    layer.tool = std::move(tool);
    EditRequest r;
    r.label = "add " + name;
    r.run = [layer](EditSession& s) { return s.addLayer(layer); };
    r.done = [this](const EditResult& res) {
        if (res.status && view_) selected_layer_ = static_cast<int>(view_->layers.layers.size()) - 1;
    };
    submit(std::move(r));
}

}  // namespace terrasynth::editor
