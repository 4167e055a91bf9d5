// Local re-synthesis after an edit (s5.3): Free inside the edit, Coherent in a band, Frozen beyond.
// Frozen pixels do not depend on their neighbours, so a window reaching a synthesis margin beyond
// the band computes exactly what a full re-synthesis with the same weights would.
#include "terrasynth/incremental.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "synth/curve_geometry.h"
#include "synth/synthesis_plan.h"

namespace terrasynth {
namespace {

PixelWindow intersect(const PixelWindow& a, const PixelWindow& b) {
    const int64_t x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
    const int64_t x1 = std::min(a.x + a.width, b.x + b.width), y1 = std::min(a.y + a.height, b.y + b.height);
    if (x1 <= x0 || y1 <= y0) return {x0, y0, 0, 0};
    return {x0, y0, static_cast<int>(x1 - x0), static_cast<int>(y1 - y0)};
}

PixelWindow grow(const PixelWindow& w, int by) { return {w.x - by, w.y - by, w.width + 2 * by, w.height + 2 * by}; }

// Copies the window's history into the extent's, level by level, pass by pass, by global position.
// Only the window's valid part at each level (its region minus the margin) is trusted.
void mergeHistory(SynthesisHistory& into, const SynthesisHistory& update, int margin) {
    for (size_t level = 0; level < update.levels.size() && level < into.levels.size(); ++level) {
        const auto& from = update.levels[level];
        auto& to = into.levels[level];
        if (from.width == 0 || to.width == 0) continue;
        for (size_t pass = 0; pass < from.passes.size() && pass < to.passes.size(); ++pass) {
            for (int y = margin; y < from.height - margin; ++y) {
                const int ty = from.y + y - to.y;
                if (ty < 0 || ty >= to.height) continue;
                for (int x = margin; x < from.width - margin; ++x) {
                    const int tx = from.x + x - to.x;
                    if (tx < 0 || tx >= to.width) continue;
                    const size_t f = static_cast<size_t>(y) * from.width + x, t = static_cast<size_t>(ty) * to.width + tx;
                    to.passes[pass].index[t] = from.passes[pass].index[f];
                    to.passes[pass].v[t] = from.passes[pass].v[f];
                }
            }
        }
    }
}

}  // namespace

Result<IncrementalTerrain> IncrementalTerrain::create(Synthesizer& synthesizer, const PixelWindow& extent,
                                                      SynthesisParams params) {
    IncrementalTerrain terrain(synthesizer, extent, std::move(params));
    terrain.params_.record_history = true;
    terrain.params_.previous.reset();
    terrain.params_.coherence.reset();
    auto out = synthesizer.synthesize(extent, terrain.params_, 0, false);
    if (!out) return out.status();
    terrain.heights_ = std::move(out->heights);
    terrain.history_ = std::move(out->history);
    terrain.last_window_ = extent;
    return terrain;
}

namespace {

bool samePoint(const PointConstraint& a, const PointConstraint& b) { return a.samePlacement(b) && a.lift_m == b.lift_m; }

bool sameCurve(const CurveConstraint& a, const CurveConstraint& b) {
    if (a.course != b.course || a.spline != b.spline || a.widgets.size() != b.widgets.size()) return false;
    for (size_t i = 0; i < a.widgets.size(); ++i) {
        const CurveWidget &u = a.widgets[i], &v = b.widgets[i];
        if (u.t != v.t || u.height_m != v.height_m || u.left_gradient != v.left_gradient ||
            u.right_gradient != v.right_gradient || u.left_reach_px != v.left_reach_px || u.right_reach_px != v.right_reach_px)
            return false;
    }
    return true;
}

uint8_t paintedAt(const TypePaint& paint, int64_t x, int64_t y) {
    if (paint.empty() || x < paint.x || y < paint.y || x >= paint.x + paint.width || y >= paint.y + paint.height)
        return TypePaint::kUnpainted;
    return paint.types[static_cast<size_t>(y - paint.y) * paint.width + (x - paint.x)];
}

}  // namespace

IncrementalTerrain::EditArea IncrementalTerrain::areaAffectedBy(const SynthesisConstraints* next) const {
    static const SynthesisConstraints kNone;
    const SynthesisConstraints& a = params_.constraints ? *params_.constraints : kNone;
    const SynthesisConstraints& b = next ? *next : kNone;
    EditArea area;
    area.mask.assign(static_cast<size_t>(extent_.width) * extent_.height, 0);
    int64_t x0 = INT64_MAX, y0 = INT64_MAX, x1 = INT64_MIN, y1 = INT64_MIN;
    auto mark = [&](int64_t gx, int64_t gy) {
        if (gx < extent_.x || gy < extent_.y || gx >= extent_.x + extent_.width || gy >= extent_.y + extent_.height) return;
        area.mask[static_cast<size_t>(gy - extent_.y) * extent_.width + (gx - extent_.x)] = 1;
        x0 = std::min(x0, gx), y0 = std::min(y0, gy), x1 = std::max(x1, gx + 1), y1 = std::max(y1, gy + 1);
    };
    auto disc = [&](double cx, double cy, double r) {
        for (int64_t y = static_cast<int64_t>(std::floor(cy - r)); y <= static_cast<int64_t>(std::ceil(cy + r)); ++y)
            for (int64_t x = static_cast<int64_t>(std::floor(cx - r)); x <= static_cast<int64_t>(std::ceil(cx + r)); ++x)
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) mark(x, y);
    };
    // Points and curves that are in one set and not the other: their whole area of effect (s5.3).
    auto pointsOnlyIn = [&](const SynthesisConstraints& from, const SynthesisConstraints& other) {
        for (const PointConstraint& p : from.points)
            if (std::none_of(other.points.begin(), other.points.end(), [&](const PointConstraint& q) { return samePoint(p, q); }))
                disc(p.x, p.y, p.radius_px);
        for (const CurveConstraint& c : from.curves) {
            if (std::any_of(other.curves.begin(), other.curves.end(), [&](const CurveConstraint& d) { return sameCurve(c, d); }))
                continue;
            float reach = 0.0f;
            for (const CurveWidget& w : c.widgets) reach = std::max({reach, w.left_reach_px, w.right_reach_px});
            const auto course = synth::cachedCourse(c);
            for (size_t i = 0; i < course->x.size(); ++i) disc(course->x[i], course->y[i], reach + 1.0);
        }
    };
    pointsOnlyIn(a, b);
    pointsOnlyIn(b, a);
    // Type painting: the pixels whose painted type changed.
    if (!a.types.empty() || !b.types.empty())
        for (int y = 0; y < extent_.height; ++y)
            for (int x = 0; x < extent_.width; ++x)
                if (paintedAt(a.types, extent_.x + x, extent_.y + y) != paintedAt(b.types, extent_.x + x, extent_.y + y))
                    mark(extent_.x + x, extent_.y + y);
    if (x1 > x0) area.box = {x0, y0, static_cast<int>(x1 - x0), static_cast<int>(y1 - y0)};
    else area.box = {extent_.x, extent_.y, 0, 0};
    return area;
}

Status IncrementalTerrain::applyEdit(std::shared_ptr<const SynthesisConstraints> next, PixelWindow* changed) {
    const EditArea area = areaAffectedBy(next.get());
    if (changed) *changed = area.box;
    if (area.box.width == 0) {
        params_.constraints = std::move(next);
        return Status::ok();
    }
    return resynthesize(area.box, &area.mask, std::move(next), hold_point_heights_);
}

Status IncrementalTerrain::update(std::shared_ptr<const SynthesisConstraints> constraints, const PixelWindow& changed) {
    return resynthesize(changed, nullptr, std::move(constraints), hold_point_heights_);
}

// Free inside `free_area` (or where `free_mask`, over the extent, is set), Coherent in a band around
// it, Frozen beyond and wherever a paste froze the terrain; re-synthesizes that window only.
Status IncrementalTerrain::resynthesize(const PixelWindow& free_area, const std::vector<uint8_t>* free_mask,
                                        std::shared_ptr<const SynthesisConstraints> constraints, bool lift_points) {
    const PixelWindow band = grow(free_area, kCoherentBand);
    // Frozen pixels reached by the window's own margin (2 pixels per subpass at level 0) settle
    // the band's neighbourhoods exactly as a full synthesis would.
    const PixelWindow window = intersect(grow(band, synth::kSubpassReach * 4 * params_.correction_passes), extent_);
    if (window.width == 0) return Status::ok();
    if (frozen_.empty()) frozen_.assign(static_cast<size_t>(extent_.width) * extent_.height, 0);
    auto map = std::make_shared<CoherenceMap>();
    map->x = window.x, map->y = window.y, map->width = window.width, map->height = window.height;
    map->outside = Coherence::Frozen;
    map->weights.assign(static_cast<size_t>(window.width) * window.height, Coherence::Frozen);
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x) {
            const int64_t gx = window.x + x, gy = window.y + y;
            const size_t e = static_cast<size_t>(gy - extent_.y) * extent_.width + (gx - extent_.x);
            auto inside = [&](const PixelWindow& w) { return gx >= w.x && gy >= w.y && gx < w.x + w.width && gy < w.y + w.height; };
            const bool free = free_mask ? inside(free_area) && (*free_mask)[e] : inside(free_area);
            Coherence c = free ? Coherence::Free : (inside(band) ? Coherence::Coherent : Coherence::Frozen);
            if (frozen_[e]) c = Coherence::Frozen;
            map->weights[static_cast<size_t>(y) * window.width + x] = c;
        }
    SynthesisParams params = params_;
    params.constraints = std::move(constraints);
    params.previous = history_;
    params.coherence = map;
    if (lift_points && params.constraints && !params.constraints->points.empty()) {
        PointLiftOptions lift;
        lift.sites_within = free_area;
        auto lifted = liftPointConstraints(*synthesizer_, params, lift);
        if (!lifted) return lifted.status();
        params.constraints = std::move(lifted.value());
    }
    params.record_history = true;
    auto out = synthesizer_->synthesize(window, params, 0, false);
    if (!out) return out.status();
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x)
            heights_.at(static_cast<int>(window.x - extent_.x) + x, static_cast<int>(window.y - extent_.y) + y) =
                out->heights.at(x, y);
    // The synthesis has finished reading the history, and nothing else holds it: merge in place.
    params.previous.reset();
    mergeHistory(*history_, *out->history, synth::kSubpassReach * 4 * params_.correction_passes);
    params_.constraints = params.constraints;
    last_window_ = window;
    return Status::ok();
}

namespace {

bool insidePolygon(const std::vector<std::pair<double, double>>& poly, double x, double y) {
    bool in = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const auto [xi, yi] = poly[i];
        const auto [xj, yj] = poly[j];
        if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
    }
    return in;
}

}  // namespace

void IncrementalTerrain::freeze(const TypePaint& mask) {
    if (frozen_.empty()) frozen_.assign(static_cast<size_t>(extent_.width) * extent_.height, 0);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            const uint8_t v = mask.types[static_cast<size_t>(y) * mask.width + x];
            const int64_t ex = mask.x + x - extent_.x, ey = mask.y + y - extent_.y;
            if (v == 0 || v == TypePaint::kUnpainted || ex < 0 || ey < 0 || ex >= extent_.width || ey >= extent_.height) continue;
            frozen_[static_cast<size_t>(ey) * extent_.width + ex] = 1;
        }
}

Status IncrementalTerrain::paste(const Paste& paste) {
    if (paste.source.size() < 3) return Status::error("paste: the source polygon needs at least 3 points");
    const ExemplarDatabase& db = synthesizer_->database();
    if (paste.exemplar >= static_cast<int>(db.exemplars.size()))
        return Status::error("paste: exemplar " + std::to_string(paste.exemplar) + " does not exist");
    if (frozen_.empty()) frozen_.assign(static_cast<size_t>(extent_.width) * extent_.height, 0);
    std::vector<std::pair<double, double>> target = paste.source;
    for (auto& [x, y] : target) x += paste.dx, y += paste.dy;
    // Write the source coordinates into every level and pass of the history at the target (s5.3:
    // "store the relevant coordinate values S^i(Omega) for all levels and sub-passes").
    const SynthesisHistory source_history = *history_;  // terrain sources read the state before the paste
    for (size_t level = 0; level < history_->levels.size(); ++level) {
        auto& l = history_->levels[level];
        if (l.width == 0) continue;
        const double cell = std::ldexp(1.0, static_cast<int>(level));
        const DatabaseLevel& dl = db.levels[level];
        for (int y = 0; y < l.height; ++y)
            for (int x = 0; x < l.width; ++x) {
                // Level-0 position of this pixel's centre.
                const double px = (l.x + x + 0.5) * cell - 0.5, py = (l.y + y + 0.5) * cell - 0.5;
                if (!insidePolygon(target, px, py)) continue;
                const double sx = px - paste.dx, sy = py - paste.dy;  // where it comes from, level 0
                for (size_t pass = 0; pass < l.passes.size(); ++pass) {
                    const size_t i = static_cast<size_t>(y) * l.width + x;
                    if (paste.exemplar >= 0) {
                        const AtlasRect& r = dl.rects[paste.exemplar];
                        const int ex = static_cast<int>(std::lround((sx + 0.5) / cell - 0.5));
                        const int ey = static_cast<int>(std::lround((sy + 0.5) / cell - 0.5));
                        if (ex < kInteriorMargin || ey < kInteriorMargin || ex >= r.width - kInteriorMargin ||
                            ey >= r.height - kInteriorMargin)
                            return Status::error("paste: source polygon leaves exemplar " +
                                                 db.exemplars[paste.exemplar].name + " at level " + std::to_string(level));
                        l.passes[pass].index[i] = static_cast<uint32_t>((r.y + ey) * dl.width + r.x + ex);
                        l.passes[pass].v[i] = paste.height_offset_m;
                    } else {
                        const auto& sl = source_history.levels[level];
                        const int hx = static_cast<int>(std::lround((sx + 0.5) / cell - 0.5)) - sl.x;
                        const int hy = static_cast<int>(std::lround((sy + 0.5) / cell - 0.5)) - sl.y;
                        if (hx < 0 || hy < 0 || hx >= sl.width || hy >= sl.height)
                            return Status::error("paste: source polygon leaves the terrain at level " + std::to_string(level));
                        const size_t f = static_cast<size_t>(hy) * sl.width + hx;
                        l.passes[pass].index[i] = sl.passes[pass].index[f];
                        l.passes[pass].v[i] = sl.passes[pass].v[f] + paste.height_offset_m;
                    }
                }
            }
    }
    // Freeze the target; the band around it is re-synthesized Free so the surroundings blend.
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (auto [x, y] : target) x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    const PixelWindow box = intersect({static_cast<int64_t>(std::floor(x0)), static_cast<int64_t>(std::floor(y0)),
                                       static_cast<int>(std::ceil(x1 - x0)) + 1, static_cast<int>(std::ceil(y1 - y0)) + 1},
                                      extent_);
    for (int64_t y = box.y; y < box.y + box.height; ++y)
        for (int64_t x = box.x; x < box.x + box.width; ++x)
            if (insidePolygon(target, static_cast<double>(x), static_cast<double>(y)))
                frozen_[static_cast<size_t>(y - extent_.y) * extent_.width + (x - extent_.x)] = 1;
    return resynthesize(grow(box, kCoherentBand), nullptr, params_.constraints, false);
}

}  // namespace terrasynth
