// What the editor draws over the 3D view: the extent's border, point handles and their reach, curve
// courses with their widgets, reach bands and junctions, pastes and the selected layer's geometry;
// then every tool's own overlay (tools/editor_tool.h). Painted types and frozen areas are coloured
// on the terrain itself (the type colours of the terrain's look, fed by EditWorker's overlay source).
#include "overlay.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "editor_app.h"

namespace terrasynth::editor {
using namespace overlay_colours;

OverlayPainter::OverlayPainter(const EditorActions& editor, std::map<std::string, ImVec4>& items)
    : editor_(editor), items_(items), draw_list_(ImGui::GetBackgroundDrawList()) {
    const PixelWindow& e = editor.view().extent;
    sample_px_ = std::max(2.0, std::max(e.width, e.height) / 128.0);
}

bool OverlayPainter::room(int vertices) {
    // Below 2^16 with a margin for what the tools draw after (their own overlays call no room()).
    constexpr unsigned kVertexBudget = 60000;
    return draw_list_->_VtxCurrentIdx + static_cast<unsigned>(vertices) < kVertexBudget;
}

void OverlayPainter::drape(const Polyline& line, bool closed, ImU32 colour, float thickness) {
    std::vector<ImVec2> run;
    auto flush = [&] {
        // An anti-aliased thick polyline takes up to 4 vertices a point.
        if (run.size() > 1 && room(4 * static_cast<int>(run.size()) + 8)) draw_list_->AddPolyline(run.data(), static_cast<int>(run.size()), colour, 0, thickness);
        run.clear();
    };
    const size_t n = line.size();
    for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
        const auto& a = line[i];
        const auto& b = line[(i + 1) % n];
        const int steps = std::max(1, static_cast<int>(std::hypot(b.first - a.first, b.second - a.second) / sample_px_));
        for (int k = (i == 0 ? 0 : 1); k <= steps; ++k) {
            const double f = static_cast<double>(k) / steps;
            const auto s = editor_.screenOfPixel(a.first + f * (b.first - a.first), a.second + f * (b.second - a.second));
            if (!s) {
                flush();
                continue;
            }
            run.push_back(ImVec2(static_cast<float>(s->x()), static_cast<float>(s->y())));
        }
    }
    flush();
}

void OverlayPainter::circle(double cx, double cy, double r, ImU32 colour, float thickness) {
    Polyline ring;
    for (int k = 0; k < 48; ++k) {
        const double a = 2.0 * M_PI * k / 48.0;
        ring.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
    }
    drape(ring, true, colour, thickness);
}

void OverlayPainter::handle(double px, double py, ImU32 colour, float radius, const std::string& item) {
    if (const auto s = editor_.screenOfPixel(px, py)) {
        const ImVec2 c(static_cast<float>(s->x()), static_cast<float>(s->y()));
        if (!item.empty()) items_[item] = ImVec4(c.x - radius, c.y - radius, c.x + radius, c.y + radius);
        if (!room(512)) return;  // a filled circle and its ring, at most 64 segments each
        draw_list_->AddCircleFilled(c, radius, colour);
        draw_list_->AddCircle(c, radius + 1.0f, IM_COL32(0, 0, 0, 200), 0, 1.5f);
    }
}

void OverlayPainter::ring(double px, double py, float radius, ImU32 colour, float thickness) {
    if (const auto s = editor_.screenOfPixel(px, py); s && room(256))
        draw_list_->AddCircle(ImVec2(float(s->x()), float(s->y())), radius, colour, 0, thickness);
}

void OverlayPainter::screenPolyline(const std::vector<osg::Vec2d>& points, ImU32 colour, float thickness) {
    std::vector<ImVec2> pts;
    for (const osg::Vec2d& p : points) pts.push_back(ImVec2(float(p.x()), float(p.y())));
    if (!room(4 * static_cast<int>(pts.size()) + 8)) return;
    draw_list_->AddPolyline(pts.data(), static_cast<int>(pts.size()), colour, 0, thickness);
}

namespace {

// Points at signed distance side(t) to the left of the course (left of travel: x east, y south).
Polyline offsetLine(const Polyline& line, const std::function<double(double)>& side) {
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
}

// A widget's reach at t along the course: linear between the widgets around t (the session
// interpolates by Hermite curves).
double reachAt(const std::vector<CurveWidget>& w, double t, bool left) {
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
}

}  // namespace

void EditorApp::drawOverlays() {
    if (!terrain_ || !view_) return;
    OverlayPainter paint(*this, items_);
    const PixelWindow& e = view_->extent;
    paint.drape({{double(e.x), double(e.y)}, {double(e.x + e.width), double(e.y)}, {double(e.x + e.width), double(e.y + e.height)},
                 {double(e.x), double(e.y + e.height)}},
                true, kExtent, 1.5f);

    // Points: reach and handle (handles are script items, so scripts can grab them).
    for (size_t i = 0; i < view_->points.size(); ++i) {
        const PointItem& p = view_->points[i];
        const bool selected = p.id == selection_.point;
        if (*show_reach_ || selected) paint.circle(p.point.x, p.point.y, p.point.radius_px, selected ? kSelected : kReach, 1.5f);
        paint.handle(p.point.x, p.point.y, selected ? kSelected : kHandle, 6.0f, "handle.point." + std::to_string(i));
    }

    // Curves: course, reach bands, widgets, junctions.
    for (const CurveItem& c : view_->curves) {
        const bool selected = c.id == selection_.curve;
        const auto& w = c.curve.widgets;
        if (*show_reach_ || selected) {
            paint.drape(offsetLine(c.curve.course, [&](double t) { return reachAt(w, t, true); }), false, kBand, 1.2f);
            paint.drape(offsetLine(c.curve.course, [&](double t) { return -reachAt(w, t, false); }), false, kBand, 1.2f);
        }
        paint.drape(c.curve.course, false, selected ? kSelected : kCourse, selected ? 3.0f : 2.0f);
        for (size_t i = 0; i < w.size(); ++i) {
            const auto at = pointAtFraction(c.curve.course, w[i].t);
            paint.handle(at.first, at.second, selected && static_cast<int>(i) == selection_.widget ? kSelected : kCourse, 5.0f,
                         selected ? "handle.widget." + std::to_string(i) : "");
        }
    }
    for (size_t i = 0; i < view_->curves.size(); ++i) {
        std::vector<std::pair<double, double>> joins = selfCrossings(view_->curves[i].curve.course);
        for (size_t j = i + 1; j < view_->curves.size(); ++j) {
            auto more = crossings(view_->curves[i].curve.course, view_->curves[j].curve.course);
            joins.insert(joins.end(), more.begin(), more.end());
        }
        for (const auto& p : joins) paint.ring(p.first, p.second, 8.0f, kJunction, 2.5f);
    }

    // Pastes.
    for (const PasteItem& p : view_->pastes) {
        Polyline target = p.paste.source;
        for (auto& q : target) q.first += p.paste.dx, q.second += p.paste.dy;
        paint.drape(target, true, p.id == selection_.paste ? kSelected : kPaste, 2.0f);
    }

    // The selected layer's geometry.
    if (selection_.layer >= 0 && selection_.layer < static_cast<int>(view_->layers.layers.size())) {
        const ToolParams& tool = view_->layers.layers[static_cast<size_t>(selection_.layer)].tool;
        if (const auto* peak = std::get_if<PeakParams>(&tool)) {
            paint.handle(peak->center_x + e.x, peak->center_y + e.y, kSelected, 5.0f);
            paint.circle(peak->center_x + e.x, peak->center_y + e.y, 2.0 * peak->spread_px, kReach, 1.2f);
        } else if (const auto* ridge = std::get_if<RidgeParams>(&tool)) {
            Polyline line;
            for (const auto& p : ridge->points) line.push_back({p[0] + e.x, p[1] + e.y});
            paint.drape(line, false, kSelected, 2.0f);
        }
    }

    // What the tools have pending, and the active tool's cursor and drag.
    for (const auto& tool : tools_) tool->drawOverlay(paint, tool.get() == tool_);
}

}  // namespace terrasynth::editor
