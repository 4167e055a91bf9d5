// What the editor draws over the 3D view with ImGui's background draw list (no GL here): the
// extent's border, point handles and their reach, curve courses with their widgets, reach bands and
// junctions, pastes, brush and region cursors, sketches in progress. Shapes lie on the terrain as
// drawn (TerrainNode::heightAt). Painted types and frozen areas are coloured on the terrain itself
// (the type colours of the terrain's look, fed by EditWorker's overlay source).
#include <cmath>

#include "editor_app.h"

namespace terrasynth::editor {
namespace {

constexpr ImU32 kExtent = IM_COL32(255, 255, 255, 90);
constexpr ImU32 kHandle = IM_COL32(255, 210, 60, 255), kSelected = IM_COL32(255, 80, 60, 255);
constexpr ImU32 kReach = IM_COL32(255, 210, 60, 110);
constexpr ImU32 kCourse = IM_COL32(80, 200, 255, 255), kBand = IM_COL32(80, 200, 255, 90);
constexpr ImU32 kJunction = IM_COL32(255, 60, 200, 255);
constexpr ImU32 kPaste = IM_COL32(170, 255, 120, 220), kGhost = IM_COL32(170, 255, 120, 120);
constexpr ImU32 kSketch = IM_COL32(255, 255, 255, 230);

}  // namespace

void EditorApp::drawOverlays() {
    if (!terrain_ || !view_) return;
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    const PixelWindow& e = view_->extent;
    const double sample_px = std::max(2.0, std::max(e.width, e.height) / 128.0);

    // A polyline of level-0 pixels draped on the terrain (subdivided so it follows the relief).
    auto drape = [&](const Polyline& line, bool closed, ImU32 colour, float thickness) {
        std::vector<ImVec2> run;
        auto flush = [&] {
            if (run.size() > 1) dl->AddPolyline(run.data(), static_cast<int>(run.size()), colour, 0, thickness);
            run.clear();
        };
        const size_t n = line.size();
        for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
            const auto& a = line[i];
            const auto& b = line[(i + 1) % n];
            const int steps = std::max(1, static_cast<int>(std::hypot(b.first - a.first, b.second - a.second) / sample_px));
            for (int k = (i == 0 ? 0 : 1); k <= steps; ++k) {
                const double f = static_cast<double>(k) / steps;
                const auto s = screenOfPixel(a.first + f * (b.first - a.first), a.second + f * (b.second - a.second));
                if (!s) {
                    flush();
                    continue;
                }
                run.push_back(ImVec2(static_cast<float>(s->x()), static_cast<float>(s->y())));
            }
        }
        flush();
    };
    auto circle = [&](double cx, double cy, double r, ImU32 colour, float thickness) {
        Polyline ring;
        for (int k = 0; k < 48; ++k) {
            const double a = 2.0 * M_PI * k / 48.0;
            ring.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
        }
        drape(ring, true, colour, thickness);
    };
    // Handles are script items too ("handle.point.0"), so scripts can grab them.
    auto handle = [&](double px, double py, ImU32 colour, float radius, const std::string& item = "") {
        if (const auto s = screenOfPixel(px, py)) {
            const ImVec2 c(static_cast<float>(s->x()), static_cast<float>(s->y()));
            dl->AddCircleFilled(c, radius, colour);
            dl->AddCircle(c, radius + 1.0f, IM_COL32(0, 0, 0, 200), 0, 1.5f);
            if (!item.empty()) items_[item] = ImVec4(c.x - radius, c.y - radius, c.x + radius, c.y + radius);
        }
    };
    auto offsetLine = [](const Polyline& line, const std::function<double(double)>& side) {
        // Points at signed distance side(t) to the left of the course (left of travel: x east, y south).
        Polyline out;
        const double total = polylineLength(line);
        double walked = 0.0;
        for (size_t i = 0; i < line.size(); ++i) {
            const auto& prev = line[i == 0 ? 0 : i - 1];
            const auto& next = line[i + 1 < line.size() ? i + 1 : i];
            double dx = next.first - prev.first, dy = next.second - prev.second;
            const double len = std::hypot(dx, dy);
            if (len <= 0.0) continue;
            dx /= len, dy /= len;
            if (i > 0) walked += std::hypot(line[i].first - line[i - 1].first, line[i].second - line[i - 1].second);
            const double d = side(total > 0.0 ? walked / total : 0.0);
            // Left of (dx, dy) in a y-south frame is (dy, -dx).
            out.push_back({line[i].first + dy * d, line[i].second - dx * d});
        }
        return out;
    };

    drape({{double(e.x), double(e.y)}, {double(e.x + e.width), double(e.y)}, {double(e.x + e.width), double(e.y + e.height)},
           {double(e.x), double(e.y + e.height)}},
          true, kExtent, 1.5f);

    // Points: reach and handle.
    for (size_t i = 0; i < view_->points.size(); ++i) {
        const PointItem& p = view_->points[i];
        const bool selected = p.id == selected_point_;
        if (show_reach_ || selected) circle(p.point.x, p.point.y, p.point.radius_px, selected ? kSelected : kReach, 1.5f);
        handle(p.point.x, p.point.y, selected ? kSelected : kHandle, 6.0f, "handle.point." + std::to_string(i));
    }

    // Curves: course, reach bands, widgets, junctions.
    for (const CurveItem& c : view_->curves) {
        const bool selected = c.id == selected_curve_;
        const auto& w = c.curve.widgets;
        auto reach = [&w](double t, bool left) {
            // Linear between the widgets around t (the session interpolates by Hermite curves).
            if (w.empty()) return 0.0;
            if (t <= w.front().t) return double(left ? w.front().left_reach_px : w.front().right_reach_px);
            for (size_t i = 1; i < w.size(); ++i)
                if (t <= w[i].t) {
                    const double f = (t - w[i - 1].t) / std::max(w[i].t - w[i - 1].t, 1e-9);
                    const double a = left ? w[i - 1].left_reach_px : w[i - 1].right_reach_px;
                    const double b = left ? w[i].left_reach_px : w[i].right_reach_px;
                    return a + f * (b - a);
                }
            return double(left ? w.back().left_reach_px : w.back().right_reach_px);
        };
        if (show_reach_ || selected) {
            drape(offsetLine(c.curve.course, [&](double t) { return reach(t, true); }), false, kBand, 1.2f);
            drape(offsetLine(c.curve.course, [&](double t) { return -reach(t, false); }), false, kBand, 1.2f);
        }
        drape(c.curve.course, false, selected ? kSelected : kCourse, selected ? 3.0f : 2.0f);
        for (size_t i = 0; i < w.size(); ++i) {
            const auto at = pointAtFraction(c.curve.course, w[i].t);
            handle(at.first, at.second, selected && static_cast<int>(i) == selected_widget_ ? kSelected : kCourse, 5.0f,
                   selected ? "handle.widget." + std::to_string(i) : "");
        }
    }
    for (size_t i = 0; i < view_->curves.size(); ++i) {
        std::vector<std::pair<double, double>> joins = selfCrossings(view_->curves[i].curve.course);
        for (size_t j = i + 1; j < view_->curves.size(); ++j) {
            auto more = crossings(view_->curves[i].curve.course, view_->curves[j].curve.course);
            joins.insert(joins.end(), more.begin(), more.end());
        }
        for (const auto& p : joins)
            if (const auto s = screenOfPixel(p.first, p.second))
                dl->AddCircle(ImVec2(float(s->x()), float(s->y())), 8.0f, kJunction, 0, 2.5f);
    }

    // Pastes and the piece being placed.
    for (const PasteItem& p : view_->pastes) {
        Polyline target = p.paste.source;
        for (auto& q : target) q.first += p.paste.dx, q.second += p.paste.dy;
        drape(target, true, p.id == selected_paste_ ? kSelected : kPaste, 2.0f);
    }
    if (!paste_source_.empty() && paste_exemplar_ < 0) drape(paste_source_, true, kGhost, 1.5f);
    if (ghost_offset_px_) {
        Polyline ghost;
        if (drag_.kind == Drag::Kind::MovePaste) {
            if (const PasteItem* p = view_->findPaste(selected_paste_))
                for (const auto& q : p->paste.source)
                    ghost.push_back({q.first + p->paste.dx + ghost_offset_px_->first, q.second + p->paste.dy + ghost_offset_px_->second});
        } else if (paste_exemplar_ < 0) {
            for (const auto& q : paste_source_) ghost.push_back({q.first + ghost_offset_px_->first, q.second + ghost_offset_px_->second});
        }
        drape(ghost, true, kPaste, 2.0f);
    }
    if (layer_paste_source_) {
        const Region& r = *layer_paste_source_;
        const double x0 = r.x + e.x, y0 = r.y + e.y;
        drape({{x0, y0}, {x0 + r.width, y0}, {x0 + r.width, y0 + r.height}, {x0, y0 + r.height}}, true, kGhost, 1.5f);
    }

    // The selected layer's geometry.
    if (selected_layer_ >= 0 && selected_layer_ < static_cast<int>(view_->layers.layers.size())) {
        const ToolParams& tool = view_->layers.layers[static_cast<size_t>(selected_layer_)].tool;
        if (const auto* peak = std::get_if<PeakParams>(&tool)) {
            handle(peak->center_x + e.x, peak->center_y + e.y, kSelected, 5.0f);
            circle(peak->center_x + e.x, peak->center_y + e.y, 2.0 * peak->spread_px, kReach, 1.2f);
        } else if (const auto* ridge = std::get_if<RidgeParams>(&tool)) {
            Polyline line;
            for (const auto& p : ridge->points) line.push_back({p[0] + e.x, p[1] + e.y});
            drape(line, false, kSelected, 2.0f);
        }
    }

    // Tools in progress.
    if (drag_.kind == Drag::Kind::Sketch || drag_.kind == Drag::Kind::Lasso) drape(drag_.stroke_px, false, kSketch, 2.0f);
    if (drag_.kind == Drag::Kind::Perspective && drag_.stroke_screen.size() > 1) {
        std::vector<ImVec2> pts;
        for (const osg::Vec2d& p : drag_.stroke_screen) pts.push_back(ImVec2(float(p.x()), float(p.y())));
        dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), kSketch, 0, 2.5f);
    }
    if (drag_.kind == Drag::Kind::Region && drag_.press_px) {
        if (const auto now = pickPixel(drag_.last_screen.x(), drag_.last_screen.y())) {
            const double x0 = drag_.press_px->first, y0 = drag_.press_px->second, x1 = now->first, y1 = now->second;
            drape({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, true, kSketch, 1.5f);
        }
    }
    const bool brush = tool_ == Tool::Paint || tool_ == Tool::Freeze;
    if (brush) {
        const std::optional<std::pair<double, double>> at =
            drag_.kind == Drag::Kind::Brush && !drag_.stroke_px.empty() ? std::optional(drag_.stroke_px.back()) : hover_px_;
        if (at) circle(at->first, at->second, tool_options_.brush_radius_px, kSketch, 1.5f);
    }
}

}  // namespace terrasynth::editor
