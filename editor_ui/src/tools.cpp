// The tools: what a left press, drag and release on the terrain do (Gain et al. 2015 s3, s5;
// Bradbury et al. 2014 s4). Each finished interaction is one undo step: single edits are one
// request, drags are bracketed by a session gesture.
#include <algorithm>
#include <cmath>

#include "editor_app.h"
#include "tool_helpers.h"

namespace terrasynth::editor {
using namespace tools;

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
            addLayer("peak", peak);
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
    if (drag_.gesture) endGesture(drag_.kind == Drag::Kind::MovePoint || drag_.kind == Drag::Kind::MoveWidget);
    ghost_offset_px_.reset();
    drag_ = Drag{};
}

void EditorApp::movePointTo(EditId id, double dx, double dy) {
    if (drag_.stroke_px.empty()) return;
    // From the site where the drag started (the view may already show intermediate moves).
    const double x = std::round(drag_.stroke_px.front().first + dx), y = std::round(drag_.stroke_px.front().second + dy);
    submitDragStep(InputKind::PointDrag, "move point", "point-drag", [id, x, y](EditSession& s) { return s.movePoint(id, x, y); });
}

void EditorApp::moveWidgetTo(double px, double py) {
    const CurveItem* c = view_->findCurve(selected_curve_);
    if (!c || selected_widget_ < 0 || selected_widget_ >= static_cast<int>(c->curve.widgets.size())) return;
    const double t = nearestOnPolyline(c->curve.course, px, py).t;
    const EditId id = selected_curve_;
    const int index = selected_widget_;
    // Widgets stay sorted by t: the dragged one may change its index.
    submitDragStep(InputKind::WidgetDrag, "move widget", "widget-drag",
                   [id, index, t](EditSession& s) { return s.moveWidget(id, index, t); },
                   [this, t](const EditResult& res) {
                       if (!res.status || !view_) return;
                       if (const CurveItem* cur = view_->findCurve(selected_curve_))
                           for (size_t i = 0; i < cur->curve.widgets.size(); ++i)
                               if (cur->curve.widgets[i].t == t) selected_widget_ = static_cast<int>(i);
                   });
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
