// The tools: what a left press, drag and release on the terrain do (Gain et al. 2015 s3, s5;
// Bradbury et al. 2014 s4). Each finished interaction is one undo step: single edits are one
// request, drags are bracketed by a session gesture.
#include <algorithm>
#include <cmath>

#include "editor_app.h"

namespace terrasynth::editor {
namespace {

constexpr double kHandlePx = 12.0;        // how close the pointer must be to grab a handle
constexpr double kCourseSpacingPx = 6.0;  // level-0 pixels between kept course points
constexpr double kMinStrokeScreenPx = 6.0;

double screenDistance(const osg::Vec2d& a, const osg::Vec2d& b) { return (a - b).length(); }

Region regionBetween(std::pair<double, double> a, std::pair<double, double> b, const PixelWindow& extent,
                     RegionShape shape) {
    Region r;
    r.shape = shape;
    r.x = std::min(a.first, b.first) - extent.x;
    r.y = std::min(a.second, b.second) - extent.y;
    r.width = std::fabs(a.first - b.first);
    r.height = std::fabs(a.second - b.second);
    return r;
}

}  // namespace

std::optional<osg::Vec3d> EditorApp::pickWorld(double x, double y) const {
    if (!terrain_ || !view_) return std::nullopt;
    osg::Vec3d origin, direction;
    projection_.ray(x, y, &origin, &direction);
    const double mpp = view_->frame.meters_per_pixel;
    const double extent_m = std::max(view_->extent.width, view_->extent.height) * mpp;
    plugin::TerrainNode* t = terrain_.get();
    return pickTerrain(origin, direction, [t](double wx, double wy) { return t->heightAt(wx, wy); }, 0.5 * mpp,
                       10.0 * extent_m + camera_->distance());
}

std::optional<std::pair<double, double>> EditorApp::pickPixel(double x, double y) const {
    const auto world = pickWorld(x, y);
    if (!world) return std::nullopt;
    return std::make_pair(view_->frame.pixelX(world->x()), view_->frame.pixelY(world->y()));
}

float EditorApp::groundAtPixel(double px, double py) const {
    const GridFrame& f = view_->frame;
    if (terrain_)
        if (auto h = terrain_->heightAt(f.worldX(px), f.worldY(py))) return *h;
    return 0.5f * (view_->min_height_m + view_->max_height_m);
}

std::optional<osg::Vec2d> EditorApp::screenOfPixel(double px, double py) const {
    const GridFrame& f = view_->frame;
    return projection_.toScreen(osg::Vec3d(f.worldX(px), f.worldY(py), groundAtPixel(px, py)));
}

void EditorApp::toolHover(double x, double y) {
    hover_px_ = (tool_ == Tool::Paint || tool_ == Tool::Freeze) ? pickPixel(x, y) : std::nullopt;
}

void EditorApp::toolPress(double x, double y, int mods) {
    if (!view_) return;
    drag_ = Drag{};
    drag_.press_screen = drag_.last_screen = osg::Vec2d(x, y);
    drag_.press_px = pickPixel(x, y);
    const osg::Vec2d at(x, y);
    switch (tool_) {
        case Tool::Point: {
            // Grab the nearest handle, else put a new point on the ground.
            EditId hit = 0;
            double best = kHandlePx;
            for (const PointItem& p : view_->points)
                if (auto s = screenOfPixel(p.point.x, p.point.y); s && screenDistance(*s, at) < best)
                    best = screenDistance(*s, at), hit = p.id;
            if (hit) {
                // Remember where the point was: it follows the pointer by the distance moved (a
                // handle grabbed off-centre does not jump).
                drag_.stroke_px.push_back({view_->findPoint(hit)->point.x, view_->findPoint(hit)->point.y});
                selected_point_ = hit;
                selected_curve_ = selected_paste_ = 0;
                drag_.kind = Drag::Kind::MovePoint;
                beginGesture();
                drag_.gesture = true;
                return;
            }
            if (!drag_.press_px) return setStatus("no terrain under the pointer", true);
            PointConstraint p;
            p.x = std::round(drag_.press_px->first);
            p.y = std::round(drag_.press_px->second);
            p.height_m = groundAtPixel(p.x, p.y) + tool_options_.point_raise_m;
            p.radius_px = tool_options_.point_radius_px;
            p.slope_angle_deg = tool_options_.point_slope_deg;
            p.slope_direction_deg = tool_options_.point_slope_direction_deg;
            auto id = std::make_shared<EditId>(0);
            EditRequest r;
            r.label = "add point";
            r.run = [p, id](EditSession& s) { return s.addPoint(p, id.get()); };
            r.done = [this, id](const EditResult& res) {
                if (res.status) selected_point_ = *id, selected_curve_ = selected_paste_ = 0;
            };
            submit(std::move(r));
            return;
        }
        case Tool::Curve: {
            if (const CurveItem* c = view_->findCurve(selected_curve_)) {
                for (size_t i = 0; i < c->curve.widgets.size(); ++i) {
                    const auto pos = pointAtFraction(c->curve.course, c->curve.widgets[i].t);
                    if (auto s = screenOfPixel(pos.first, pos.second); s && screenDistance(*s, at) < kHandlePx) {
                        selected_widget_ = static_cast<int>(i);
                        drag_.kind = Drag::Kind::MoveWidget;
                        beginGesture();
                        drag_.gesture = true;
                        return;
                    }
                }
            }
            drag_.kind = Drag::Kind::Sketch;
            if (drag_.press_px) drag_.stroke_px.push_back(*drag_.press_px);
            return;
        }
        case Tool::Paint:
        case Tool::Freeze:
            if (!drag_.press_px) return;
            drag_.kind = Drag::Kind::Brush;
            drag_.stroke_px.push_back(*drag_.press_px);
            beginGesture();
            drag_.gesture = true;
            toolDrag(x, y);
            return;
        case Tool::Paste: {
            if (!drag_.press_px) return;
            const PasteItem* selected = view_->findPaste(selected_paste_);
            if (selected && selected->paste.exemplar < 0) {
                Polyline target = selected->paste.source;
                for (auto& q : target) q.first += selected->paste.dx, q.second += selected->paste.dy;
                if (insidePolygon(target, drag_.press_px->first, drag_.press_px->second)) {
                    drag_.kind = Drag::Kind::MovePaste;
                    return;
                }
            }
            drag_.kind = paste_source_.empty() ? Drag::Kind::Lasso : Drag::Kind::PlacePaste;
            if (drag_.kind == Drag::Kind::Lasso) drag_.stroke_px.push_back(*drag_.press_px);
            return;
        }
        case Tool::Peak: {
            if (!drag_.press_px) return;
            PeakParams peak;
            peak.center_x = drag_.press_px->first - view_->extent.x;
            peak.center_y = drag_.press_px->second - view_->extent.y;
            peak.height_m = (mods & 1) ? -tool_options_.peak_height_m : tool_options_.peak_height_m;  // Shift digs
            peak.spread_px = tool_options_.peak_spread_px;
            EditLayer layer;
            layer.name = "peak";
            layer.tool = peak;
            layer.weights = defaultWeights(layer.tool);
            addLayer(std::move(layer), "add peak");
            return;
        }
        case Tool::Ridge:
            drag_.kind = Drag::Kind::Sketch;
            if (drag_.press_px) drag_.stroke_px.push_back(*drag_.press_px);
            return;
        case Tool::LayerPaste:
        case Tool::HoleFill:
        case Tool::Noise:
            drag_.kind = Drag::Kind::Region;
            return;
        case Tool::Perspective:
            drag_.kind = Drag::Kind::Perspective;
            drag_.stroke_screen.push_back(at);
            return;
    }
}

void EditorApp::toolDrag(double x, double y) {
    const osg::Vec2d at(x, y);
    const bool moved = screenDistance(at, drag_.last_screen) >= 2.0;
    switch (drag_.kind) {
        case Drag::Kind::MovePoint: {
            const auto now = pickPixel(x, y);
            if (!now || !drag_.press_px || !moved) return;
            movePointTo(selected_point_, now->first - drag_.press_px->first, now->second - drag_.press_px->second);
            break;
        }
        case Drag::Kind::MoveWidget: {
            if (auto now = pickPixel(x, y)) moveWidgetTo(now->first, now->second);
            break;
        }
        case Drag::Kind::Sketch:
        case Drag::Kind::Lasso:
            if (!moved) return;
            if (auto now = pickPixel(x, y)) drag_.stroke_px.push_back(*now);
            break;
        case Drag::Kind::Brush: {
            if (auto now = pickPixel(x, y); now && (moved || drag_.stroke_px.size() == 1)) {
                if (drag_.stroke_px.size() > 1 || now != drag_.stroke_px.front()) drag_.stroke_px.push_back(*now);
                // The whole stroke so far, latest wins: painting the same pixels again changes
                // nothing, so the session only re-synthesizes what is newly covered.
                const Polyline stroke = drag_.stroke_px;
                const float radius = tool_options_.brush_radius_px;
                const bool erase = tool_options_.erase;
                EditRequest r;
                r.coalesce_key = "brush";
                r.refresh_masks = true;
                if (tool_ == Tool::Paint) {
                    const std::string type = view_->database->type_names.at(
                        static_cast<size_t>(std::clamp(tool_options_.paint_type, 0, int(view_->database->type_names.size()) - 1)));
                    r.label = erase ? "erase types" : "paint " + type;
                    r.run = [stroke, radius, erase, type](EditSession& s) {
                        return erase ? s.eraseTypes(stroke, radius) : s.paintTypes(stroke, radius, type);
                    };
                } else {
                    r.label = erase ? "unfreeze" : "freeze";
                    r.run = [stroke, radius, erase](EditSession& s) {
                        return erase ? s.unfreeze(stroke, radius) : s.freeze(stroke, radius);
                    };
                }
                submit(std::move(r));
            }
            break;
        }
        case Drag::Kind::PlacePaste:
        case Drag::Kind::MovePaste:
            if (auto now = pickPixel(x, y); now && drag_.press_px)
                ghost_offset_px_ = std::make_pair(now->first - drag_.press_px->first, now->second - drag_.press_px->second);
            break;
        case Drag::Kind::Perspective:
            if (moved) drag_.stroke_screen.push_back(at);
            break;
        case Drag::Kind::Region:
        case Drag::Kind::None:
            break;
    }
    if (moved) drag_.last_screen = at;
}

void EditorApp::toolRelease(double x, double y) {
    if (drag_.kind == Drag::Kind::None) return;
    toolDrag(x, y);
    const auto release_px = pickPixel(x, y);
    switch (drag_.kind) {
        case Drag::Kind::Sketch:
            finishSketch();
            break;
        case Drag::Kind::Lasso:
            if (drag_.stroke_px.size() >= 3) {
                paste_source_ = decimate(drag_.stroke_px, 2.0);
                paste_exemplar_ = -1;
                setStatus("copied: drag the piece to where it goes (Esc to cancel)", false);
            }
            break;
        case Drag::Kind::PlacePaste: {
            if (!release_px || !drag_.press_px) break;
            double dx = release_px->first - drag_.press_px->first, dy = release_px->second - drag_.press_px->second;
            if (paste_exemplar_ >= 0) {
                // From an exemplar: the piece's centre lands where the pointer is released.
                const auto c = centroid(paste_source_);
                dx = std::round(release_px->first - c.first), dy = std::round(release_px->second - c.second);
            }
            if (paste_exemplar_ < 0 && std::hypot(dx, dy) < 1.0) {
                setStatus("drag the copied piece to where it goes", false);
                break;
            }
            placePaste(std::round(dx), std::round(dy), std::nullopt);
            break;
        }
        case Drag::Kind::MovePaste: {
            const PasteItem* p = view_->findPaste(selected_paste_);
            if (!p || !release_px || !drag_.press_px) break;
            const double dx = std::round(release_px->first - drag_.press_px->first);
            const double dy = std::round(release_px->second - drag_.press_px->second);
            if (dx != 0.0 || dy != 0.0) placePaste(p->paste.dx + dx, p->paste.dy + dy, p->id);
            break;
        }
        case Drag::Kind::Region:
            finishRegion();
            break;
        case Drag::Kind::Perspective:
            finishPerspectiveStroke();
            break;
        default:
            break;
    }
    if (drag_.gesture) endGesture();
    ghost_offset_px_.reset();
    drag_ = Drag{};
}

void EditorApp::movePointTo(EditId id, double dx, double dy) {
    if (drag_.stroke_px.empty()) return;
    // From the site where the drag started (the view may already show intermediate moves).
    const double x = std::round(drag_.stroke_px.front().first + dx), y = std::round(drag_.stroke_px.front().second + dy);
    const uint64_t seq = latency_.noteInput(InputKind::PointDrag, frame_input_s_);
    EditRequest r;
    r.label = "move point";
    r.coalesce_key = "point-drag";
    r.input_seq = seq;
    r.input_kind = static_cast<int>(InputKind::PointDrag);
    r.run = [id, x, y](EditSession& s) { return s.movePoint(id, x, y); };
    submit(std::move(r));
}

void EditorApp::moveWidgetTo(double px, double py) {
    const CurveItem* c = view_->findCurve(selected_curve_);
    if (!c || selected_widget_ < 0 || selected_widget_ >= static_cast<int>(c->curve.widgets.size())) return;
    const double t = nearestOnPolyline(c->curve.course, px, py).t;
    const uint64_t seq = latency_.noteInput(InputKind::WidgetDrag, frame_input_s_);
    EditRequest r;
    r.label = "move widget";
    r.coalesce_key = "widget-drag";
    r.input_seq = seq;
    r.input_kind = static_cast<int>(InputKind::WidgetDrag);
    const EditId id = selected_curve_;
    const int index = selected_widget_;
    r.run = [id, index, t](EditSession& s) { return s.moveWidget(id, index, t); };
    // Widgets stay sorted by t: the dragged one may change its index.
    r.done = [this, t](const EditResult& res) {
        if (!res.status || !view_) return;
        if (const CurveItem* cur = view_->findCurve(selected_curve_))
            for (size_t i = 0; i < cur->curve.widgets.size(); ++i)
                if (cur->curve.widgets[i].t == t) selected_widget_ = static_cast<int>(i);
    };
    submit(std::move(r));
}

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
        EditLayer layer;
        layer.name = "ridge";
        layer.tool = ridge;
        layer.weights = defaultWeights(layer.tool);
        addLayer(std::move(layer), "add ridge");
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
    EditLayer layer;
    if (tool_ == Tool::Noise) {
        NoiseParams noise;
        noise.fractal.amplitude_m = tool_options_.noise_amplitude_m;
        noise.fractal.wavelength_px = tool_options_.noise_wavelength_px;
        noise.fractal.octaves = 6;
        noise.fractal.seed = view_->edit_count + 1;
        if (!is_click) noise.region = regionBetween(*drag_.press_px, *end, e, RegionShape::Ellipse);
        noise.feather_px = 16.0;
        layer.name = "noise";
        layer.tool = noise;
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
            layer.name = "paste";
            layer.tool = paste;
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
        layer.name = "hole fill";
        layer.tool = fill;
    }
    layer.weights = defaultWeights(layer.tool);
    const bool hole_fill = std::holds_alternative<HoleFillParams>(layer.tool);
    addLayer(std::move(layer), std::string("add ") + toolName(tool_));
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
    EditLayer layer;
    layer.name = "perspective sketch";
    layer.tool = params;
    layer.weights = defaultWeights(layer.tool);
    addLayer(std::move(layer), "add perspective sketch");
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

void EditorApp::addLayer(EditLayer layer, const std::string& label) {
    EditRequest r;
    r.label = label;
    r.run = [layer](EditSession& s) { return s.addLayer(layer); };
    r.done = [this](const EditResult& res) {
        if (res.status && view_) selected_layer_ = static_cast<int>(view_->layers.layers.size()) - 1;
    };
    submit(std::move(r));
}

void EditorApp::deleteSelection() {
    EditRequest r;
    if (selected_point_) {
        const EditId id = selected_point_;
        r.label = "remove point";
        r.run = [id](EditSession& s) { return s.removePoint(id); };
        selected_point_ = 0;
    } else if (selected_curve_ && selected_widget_ >= 0) {
        const EditId id = selected_curve_;
        const int index = selected_widget_;
        r.label = "remove widget";
        r.run = [id, index](EditSession& s) { return s.removeWidget(id, index); };
        selected_widget_ = -1;
    } else if (selected_curve_) {
        const EditId id = selected_curve_;
        r.label = "remove curve";
        r.run = [id](EditSession& s) { return s.removeCurve(id); };
        selected_curve_ = 0;
    } else if (selected_paste_) {
        const EditId id = selected_paste_;
        r.label = "remove paste";
        r.refresh_masks = true;
        r.run = [id](EditSession& s) { return s.removePaste(id); };
        selected_paste_ = 0;
    } else {
        return;
    }
    submit(std::move(r));
}

}  // namespace terrasynth::editor
