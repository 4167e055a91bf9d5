// Local re-synthesis after an edit (s5.3): Free inside the edit, Coherent in a band, Frozen beyond.
// Frozen pixels do not depend on their neighbours, so a window reaching a synthesis margin beyond
// the band computes exactly what a full re-synthesis with the same weights would.
#include "terrasynth/incremental.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

#include "constraints/curve_geometry.h"
#include "core/tile_journal.h"
#include "synth/coherence_fields.h"
#include "synth/synthesis_driver.h"
#include "synth/synthesis_plan.h"

namespace terrasynth {
namespace {

// An edit keeps the curves' lift profiles it starts from while the median miss along the edited
// courses stays within this share of the extent's relief (the guarantee is 1%, docs/curves.md).
constexpr float kCurveHoldMedian = 0.005f;

// Copies the window's history into the extent's, level by level, pass by pass, by global position.
// Only the window's valid part at each level (its region minus the margin) is trusted. `touching`
// is told each level's rectangle (global pixels of that level) before it is written.
template <class Touch>
void mergeHistory(SynthesisHistory& into, const SynthesisHistory& update, int margin, Touch&& touching) {
    for (size_t level = 0; level < update.levels.size() && level < into.levels.size(); ++level) {
        const auto& from = update.levels[level];
        auto& to = into.levels[level];
        if (from.width == 0 || to.width == 0) continue;
        touching(static_cast<int>(level), from.x + margin, from.y + margin, from.width - 2 * margin, from.height - 2 * margin);
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

IncrementalTerrain::IncrementalTerrain(Synthesizer& s, PixelWindow extent, SynthesisParams params)
    : synthesizer_(&s), extent_(extent), params_(std::move(params)) {
    params_.record_history = true;
    params_.previous.reset();
    params_.coherence.reset();
    frozen_.assign(static_cast<size_t>(extent_.width) * extent_.height, 0);
}
IncrementalTerrain::IncrementalTerrain(IncrementalTerrain&&) noexcept = default;
IncrementalTerrain& IncrementalTerrain::operator=(IncrementalTerrain&&) noexcept = default;
IncrementalTerrain::~IncrementalTerrain() = default;

Result<IncrementalTerrain> IncrementalTerrain::create(Synthesizer& synthesizer, const PixelWindow& extent,
                                                      SynthesisParams params) {
    IncrementalTerrain terrain(synthesizer, extent, std::move(params));
    auto out = synthesizer.synthesize(extent, terrain.params_, 0, false);
    if (!out) return out.status();
    terrain.heights_ = std::move(out->heights);
    terrain.history_ = std::move(out->history);
    terrain.last_window_ = extent;
    return terrain;
}

Result<IncrementalTerrain> IncrementalTerrain::restore(Synthesizer& synthesizer, const PixelWindow& extent,
                                                       SynthesisParams params, Heightfield heights,
                                                       std::vector<uint8_t> frozen, SynthesisHistory history) {
    IncrementalTerrain terrain(synthesizer, extent, std::move(params));
    const size_t pixels = static_cast<size_t>(extent.width) * extent.height;
    if (heights.width != extent.width || heights.height != extent.height || heights.heights.size() != pixels)
        return Status::error("restored heights do not cover the extent");
    if (frozen.size() != pixels) return Status::error("restored frozen mask does not cover the extent");
    // The history must be the one a synthesis of the extent records: same regions, same passes.
    const int coarsest = synth::coarsestLevel(synthesizer.database(), terrain.params_);
    const synth::SynthesisPlan plan = synth::planSynthesis(extent, 0, coarsest, terrain.params_.correction_passes,
                                                           synth::extraMargins(terrain.params_, coarsest));
    if (history.levels.size() != plan.regions.size())
        return Status::error("restored history has " + std::to_string(history.levels.size()) + " levels, the synthesis " +
                             std::to_string(plan.regions.size()));
    for (size_t level = 0; level < plan.regions.size(); ++level) {
        const auto& want = plan.regions[level];
        const auto& got = history.levels[level];
        const size_t n = static_cast<size_t>(got.width) * got.height;
        bool fits = got.x == want.x && got.y == want.y && got.width == want.width && got.height == want.height &&
                    got.passes.size() == static_cast<size_t>(synth::historyPassesAt(terrain.params_, static_cast<int>(level), coarsest));
        for (const auto& pass : got.passes) fits = fits && pass.index.size() == n && pass.v.size() == n;
        if (!fits) return Status::error("restored history level " + std::to_string(level) + " does not fit the extent");
        // The kernels read the atlas at these indices: one past it is out of bounds, not a pixel.
        const size_t atlas = level < static_cast<size_t>(synthesizer.database().levelCount())
                                 ? synthesizer.database().levels[level].pixelCount() : 0;
        for (size_t pass = 0; pass < got.passes.size(); ++pass)
            for (size_t i = 0; i < n; ++i)
                if (got.passes[pass].index[i] >= atlas)
                    return Status::error("restored history level " + std::to_string(level) + " pass " + std::to_string(pass) +
                                         ": atlas index " + std::to_string(got.passes[pass].index[i]) + " at pixel " +
                                         std::to_string(i) + " is past the atlas of " + std::to_string(atlas) + " pixels");
    }
    terrain.heights_ = std::move(heights);
    terrain.frozen_ = std::move(frozen);
    terrain.history_ = std::make_shared<SynthesisHistory>(std::move(history));
    terrain.last_window_ = extent;
    return terrain;
}

namespace {

bool samePoint(const PointConstraint& a, const PointConstraint& b) { return a.samePlacement(b) && a.sameLifts(b); }

bool sameCurve(const CurveConstraint& a, const CurveConstraint& b) {
    if (a.course != b.course || a.spline != b.spline || a.widgets.size() != b.widgets.size() || a.lift_m != b.lift_m)
        return false;
    for (size_t i = 0; i < a.widgets.size(); ++i) {
        const CurveWidget &u = a.widgets[i], &v = b.widgets[i];
        if (u.t != v.t || u.height_m != v.height_m || u.left_gradient != v.left_gradient ||
            u.right_gradient != v.right_gradient || u.left_reach_px != v.left_reach_px || u.right_reach_px != v.right_reach_px)
            return false;
    }
    return true;
}

// Curves given without a lift profile take the one of a current curve with the same course (the
// first not yet taken): an unchanged curve keeps its lift, and an edited one starts its search there.
std::shared_ptr<const SynthesisConstraints> adoptCurveLifts(std::shared_ptr<const SynthesisConstraints> next,
                                                            const SynthesisConstraints* current) {
    if (!next || !current || current->curves.empty()) return next;
    std::vector<bool> taken(current->curves.size(), false);
    std::shared_ptr<SynthesisConstraints> adopted;
    for (size_t i = 0; i < next->curves.size(); ++i) {
        const CurveConstraint& c = next->curves[i];
        if (!c.lift_m.empty()) continue;
        for (size_t k = 0; k < current->curves.size(); ++k) {
            const CurveConstraint& d = current->curves[k];
            if (taken[k] || d.lift_m.empty() || d.course != c.course || d.spline != c.spline) continue;
            taken[k] = true;
            if (!adopted) adopted = std::make_shared<SynthesisConstraints>(*next);
            adopted->curves[i].lift_m = d.lift_m;
            break;
        }
    }
    return adopted ? adopted : next;
}

uint8_t paintedAt(const TypePaint& paint, int64_t x, int64_t y) {
    if (paint.empty() || x < paint.x || y < paint.y || x >= paint.x + paint.width || y >= paint.y + paint.height)
        return TypePaint::kUnpainted;
    return paint.types[static_cast<size_t>(y - paint.y) * paint.width + (x - paint.x)];
}

}  // namespace

IncrementalTerrain::EditArea IncrementalTerrain::areaAffectedBy(const SynthesisConstraints* next_raw) const {
    static const SynthesisConstraints kNone;
    const SynthesisConstraints& a = params_.constraints ? *params_.constraints : kNone;
    const auto next = next_raw ? adoptCurveLifts(std::make_shared<const SynthesisConstraints>(*next_raw), &a) : nullptr;
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
            const auto course = constraints::cachedCourse(c);
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
    next = adoptCurveLifts(std::move(next), params_.constraints.get());
    const EditArea area = areaAffectedBy(next.get());
    if (changed) *changed = area.box;
    if (area.box.width == 0) {
        params_.constraints = std::move(next);
        return Status::ok();
    }
    noteDeferred(area.box);
    return resynthesize(area.box, &area.mask, std::move(next), liftsNow(), previewNow());
}

Status IncrementalTerrain::update(std::shared_ptr<const SynthesisConstraints> constraints, const PixelWindow& changed) {
    noteDeferred(changed);
    return resynthesize(changed, nullptr, adoptCurveLifts(std::move(constraints), params_.constraints.get()), liftsNow(),
                        previewNow());
}

void IncrementalTerrain::noteDeferred(const PixelWindow& free_area) {
    if (lifts_deferred_ && (hold_point_heights_ || preview_levels_ > 0))
        deferred_area_ = uniteWindows(deferred_area_, free_area);
}

void IncrementalTerrain::setPreviewLevels(int levels) {
    TERRASYNTH_REQUIRE(levels >= 0 && levels <= 2, "setPreviewLevels takes 0..2 levels");
    preview_levels_ = levels;
}

Status IncrementalTerrain::liftDeferred(PixelWindow* changed) {
    const PixelWindow area = deferred_area_;
    deferred_area_ = {0, 0, 0, 0};
    if (changed) *changed = area;
    if (area.empty()) return Status::ok();
    // The whole union is re-synthesized Free (and in full after a preview): the constraints inside
    // it are lifted against the terrain it will have, not against the drag's intermediate one.
    return resynthesize(area, nullptr, params_.constraints, hold_point_heights_);
}

// Free inside `free_area` (or where `free_mask`, over the extent, is set), Coherent in a band around
// it, Frozen beyond and wherever a paste froze the terrain; re-synthesizes that window only.
Status IncrementalTerrain::resynthesize(const PixelWindow& free_area, const std::vector<uint8_t>* free_mask,
                                        std::shared_ptr<const SynthesisConstraints> constraints, bool lift_points,
                                        int preview_levels) {
    const PixelWindow band = growWindow(free_area, kCoherentBand);
    // Frozen pixels reached by the window's own margin (2 pixels per subpass at level 0) settle
    // the band's neighbourhoods exactly as a full synthesis would.
    const PixelWindow window = intersectWindows(growWindow(band, synth::kSubpassReach * 4 * params_.correction_passes), extent_);
    if (window.width == 0) return Status::ok();
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
    params.preview_levels = preview_levels;
    auto out = synthesizer_->synthesize(window, params, 0, false);
    if (!out) return out.status();
    if (lift_points && params.constraints && !params.constraints->curves.empty()) {
        // The curves' lift profiles (kept from before the edit) are searched further only when the
        // edited courses miss their heights by more than kCurveHoldMedian of the relief: dragging a
        // widget usually keeps them good, and then the edit costs one synthesis.
        CurveLiftOptions lift;
        lift.stations_within = free_area;
        const HeightRange relief = heightRange(heights_);
        lift.tolerance_m = kCurveHoldMedian * (relief.max - relief.min);
        lift.measured = &out->heights, lift.measured_x = window.x, lift.measured_y = window.y;
        auto lifted = liftCurveConstraints(*synthesizer_, params, lift);
        if (!lifted) return lifted.status();
        if (lifted.value() != params.constraints) {
            params.constraints = std::move(lifted.value());
            out = synthesizer_->synthesize(window, params, 0, false);
            if (!out) return out.status();
        }
    }
    record(0, window.x - extent_.x, window.y - extent_.y, window.width, window.height);
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x)
            heights_.at(static_cast<int>(window.x - extent_.x) + x, static_cast<int>(window.y - extent_.y) + y) =
                out->heights.at(x, y);
    // The synthesis has finished reading the history, and nothing else holds it: merge in place.
    params.previous.reset();
    mergeHistory(*history_, *out->history, synth::kSubpassReach * 4 * params_.correction_passes,
                 [&](int level, int64_t x, int64_t y, int64_t w, int64_t h) { recordHistory(level, x, y, w, h); });
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

std::vector<std::pair<double, double>> targetPolygon(const PasteConstraint& paste) {
    std::vector<std::pair<double, double>> target = paste.source;
    for (auto& [x, y] : target) x += paste.dx, y += paste.dy;
    return target;
}

// The level-0 box of a polygon, clipped to `clip`.
PixelWindow polygonBox(const std::vector<std::pair<double, double>>& polygon, const PixelWindow& clip) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (auto [x, y] : polygon) x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    const double lo = -static_cast<double>(synth::kMaxGlobalCoordinate), hi = static_cast<double>(synth::kMaxGlobalCoordinate);
    x0 = std::clamp(std::floor(x0), lo, hi), y0 = std::clamp(std::floor(y0), lo, hi);
    x1 = std::clamp(std::ceil(x1), lo, hi), y1 = std::clamp(std::ceil(y1), lo, hi);
    return intersectWindows({static_cast<int64_t>(x0), static_cast<int64_t>(y0), static_cast<int>(x1 - x0) + 1,
                             static_cast<int>(y1 - y0) + 1},
                            clip);
}

// Distance from (x, y) to the nearest edge of a closed polygon.
double distanceToPolygon(const std::vector<std::pair<double, double>>& poly, double x, double y) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const auto [ax, ay] = poly[j];
        const auto [bx, by] = poly[i];
        const double ex = bx - ax, ey = by - ay, len2 = ex * ex + ey * ey;
        const double u = len2 > 0.0 ? std::clamp(((x - ax) * ex + (y - ay) * ey) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, std::hypot(x - ax - u * ex, y - ay - u * ey));
    }
    return best;
}

// Pixels of one history level whose centres (in level-0 coordinates) lie inside `polygon`, visited
// row by row as (x, y, row-major index).
template <class Visit>
void forEachLevelPixelInside(const SynthesisHistory::Level& l, int level, const std::vector<std::pair<double, double>>& polygon,
                             Visit&& visit, double inset = 0.0) {
    const double cell = std::ldexp(1.0, level);
    const int64_t scale = int64_t(1) << level;
    const PixelWindow box = polygonBox(polygon, {l.x * scale, l.y * scale, static_cast<int>(l.width * scale),
                                                 static_cast<int>(l.height * scale)});
    if (box.empty()) return;
    const int x0 = std::max(0, static_cast<int>((box.x >> level) - l.x) - 1);
    const int y0 = std::max(0, static_cast<int>((box.y >> level) - l.y) - 1);
    const int x1 = std::min(l.width, static_cast<int>(((box.x + box.width) >> level) - l.x) + 2);
    const int y1 = std::min(l.height, static_cast<int>(((box.y + box.height) >> level) - l.y) + 2);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const double px = (l.x + x + 0.5) * cell - 0.5, py = (l.y + y + 0.5) * cell - 0.5;
            if (insidePolygon(polygon, px, py) && (inset <= 0.0 || distanceToPolygon(polygon, px, py) >= inset))
                visit(x, y, static_cast<size_t>(y) * l.width + x);
        }
}

// Level coordinate v of an exemplar `size` pixels wide, mirrored (about its interior's edges) into
// the interior [kInteriorMargin, size - 1 - kInteriorMargin]; -1 when that is empty.
long mirroredIntoInterior(long v, int size) {
    const long lo = kInteriorMargin, hi = static_cast<long>(size) - 1 - kInteriorMargin;
    if (hi < lo) return -1;
    if (hi == lo) return lo;
    const long period = 2 * (hi - lo);
    const long u = ((v - lo) % period + period) % period;
    return u <= hi - lo ? lo + u : hi - (u - (hi - lo));
}

}  // namespace

namespace {

// Level-0 pixels of `extent` whose centres lie inside `polygon`, at least `inset` from its edges.
std::vector<uint8_t> polygonMask(const std::vector<std::pair<double, double>>& polygon, const PixelWindow& extent,
                                 double inset) {
    std::vector<uint8_t> mask(static_cast<size_t>(extent.width) * extent.height, 0);
    if (polygon.size() < 3) return mask;
    const PixelWindow box = polygonBox(polygon, extent);
    for (int64_t y = box.y; y < box.y + box.height; ++y)
        for (int64_t x = box.x; x < box.x + box.width; ++x) {
            const double px = static_cast<double>(x), py = static_cast<double>(y);
            if (insidePolygon(polygon, px, py) && (inset <= 0.0 || distanceToPolygon(polygon, px, py) >= inset))
                mask[static_cast<size_t>(y - extent.y) * extent.width + (x - extent.x)] = 1;
        }
    return mask;
}

}  // namespace

std::vector<uint8_t> pasteTargetMask(const PasteConstraint& paste, const PixelWindow& extent) {
    return polygonMask(targetPolygon(paste), extent, IncrementalTerrain::kPasteBlendPx);
}

void IncrementalTerrain::freeze(const TypePaint& mask) {
    record(1, mask.x - extent_.x, mask.y - extent_.y, mask.width, mask.height);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            const uint8_t v = mask.types[static_cast<size_t>(y) * mask.width + x];
            const int64_t ex = mask.x + x - extent_.x, ey = mask.y + y - extent_.y;
            if (v == 0 || v == TypePaint::kUnpainted || ex < 0 || ey < 0 || ex >= extent_.width || ey >= extent_.height) continue;
            frozen_[static_cast<size_t>(ey) * extent_.width + ex] = 1;
        }
}

void IncrementalTerrain::setFrozen(std::vector<uint8_t> mask) {
    TERRASYNTH_REQUIRE(mask.size() == frozen_.size(), "setFrozen needs one value per extent pixel");
    for (int y = 0; y < extent_.height; ++y)
        for (int x = 0; x < extent_.width; ++x) {
            const size_t i = static_cast<size_t>(y) * extent_.width + x;
            const uint8_t v = mask[i] ? 1 : 0;
            if (frozen_[i] == v) continue;
            record(1, x, y, 1, 1);
            frozen_[i] = v;
        }
}

Status IncrementalTerrain::paste(const Paste& paste) {
    if (paste.source.size() < 3) return Status::error("paste: the source polygon needs at least 3 points");
    const ExemplarDatabase& db = synthesizer_->database();
    if (paste.exemplar >= static_cast<int>(db.exemplars.size()))
        return Status::error("paste: exemplar " + std::to_string(paste.exemplar) + " does not exist");
    if (paste.exemplar >= 0) {
        // The whole polygon lies inside the exemplar at level 0 (its pixels' areas, as resampled to
        // the database spacing), whatever part of it the extent shows.
        const AtlasRect& r = db.levels[0].rects[paste.exemplar];
        for (const auto& [x, y] : paste.source)
            if (!(x >= -0.5 && y >= -0.5 && x <= r.width - 0.5 && y <= r.height - 0.5))
                return Status::error("paste: source polygon leaves exemplar " + db.exemplars[paste.exemplar].name + " (" +
                                     std::to_string(r.width) + "x" + std::to_string(r.height) +
                                     " pixels at the database spacing)");
    }
    const auto target = targetPolygon(paste);
    const PixelWindow box = polygonBox(target, extent_);
    if (box.empty()) return Status::error("paste: the target polygon lies outside the terrain's extent");
    // s5.3: "store the relevant coordinate values S^i(Omega) for all levels and sub-passes". All
    // writes are gathered first, from the history as it was before the paste (terrain sources read
    // it), so a polygon that leaves its source changes nothing.
    struct Write {
        int level;
        size_t pass, i;
        uint32_t index;
        float v;
    };
    std::vector<Write> writes;
    for (size_t level = 0; level < history_->levels.size(); ++level) {
        const auto& l = history_->levels[level];
        if (l.width == 0) continue;
        const double cell = std::ldexp(1.0, static_cast<int>(level));
        const DatabaseLevel& dl = db.levels[level];
        Status failed = Status::ok();
        forEachLevelPixelInside(l, static_cast<int>(level), target, [&](int x, int y, size_t i) {
            if (!failed) return;
            // Where this pixel's centre comes from, in level-0 and then level coordinates.
            const double sx = (l.x + x + 0.5) * cell - 0.5 - paste.dx, sy = (l.y + y + 0.5) * cell - 0.5 - paste.dy;
            const long lx = std::lround((sx + 0.5) / cell - 0.5), ly = std::lround((sy + 0.5) / cell - 0.5);
            for (size_t pass = 0; pass < l.passes.size(); ++pass) {
                if (paste.exemplar >= 0) {
                    const AtlasRect& r = dl.rects[paste.exemplar];
                    long ex = lx, ey = ly;
                    if (level == 0) {
                        // The pasted pixels themselves: the polygon must lie inside the exemplar.
                        if (lx < 0 || ly < 0 || lx >= r.width || ly >= r.height) {
                            failed = Status::error("paste: source polygon leaves exemplar " +
                                                   db.exemplars[paste.exemplar].name + " (" + std::to_string(r.width) + "x" +
                                                   std::to_string(r.height) + " pixels at the database spacing)");
                            return;
                        }
                    } else {
                        // Coarse levels only shape what the surroundings blend towards: an exemplar
                        // narrower than the polygon at this level is mirrored into its interior, and
                        // where it has none the synthesized coarse terrain under the paste stays.
                        ex = mirroredIntoInterior(lx, r.width), ey = mirroredIntoInterior(ly, r.height);
                        if (ex < 0 || ey < 0) continue;
                    }
                    // NoData voids (and their margin) are never copied: refused at level 0, left to
                    // the synthesized coarse terrain above.
                    if (dl.type[static_cast<size_t>(r.y + ey) * dl.width + r.x + ex] == kNoType) {
                        if (level > 0) continue;
                        failed = Status::error("paste: source polygon reaches a NoData void of exemplar " +
                                               db.exemplars[paste.exemplar].name);
                        return;
                    }
                    writes.push_back({static_cast<int>(level), pass, i,
                                      static_cast<uint32_t>((r.y + ey) * dl.width + r.x + ex), paste.height_offset_m});
                } else {
                    const long hx = lx - l.x, hy = ly - l.y;
                    if (hx < 0 || hy < 0 || hx >= l.width || hy >= l.height) {
                        failed = Status::error("paste: source polygon leaves the terrain at level " + std::to_string(level));
                        return;
                    }
                    const size_t f = static_cast<size_t>(hy) * l.width + hx;
                    writes.push_back({static_cast<int>(level), pass, i, l.passes[pass].index[f],
                                      l.passes[pass].v[f] + paste.height_offset_m});
                }
            }
        }, level > 0 ? kPasteBlendPx : 0.0);  // coarse levels: the frozen part only, the rim blends there too
        if (!failed) return failed;
    }
    for (const Write& w : writes) {
        auto& l = history_->levels[w.level];
        const int64_t x = l.x + static_cast<int64_t>(w.i % l.width), y = l.y + static_cast<int64_t>(w.i / l.width);
        recordHistory(w.level, x, y, 1, 1);
        l.passes[w.pass].index[w.i] = w.index;
        l.passes[w.pass].v[w.i] = w.v;
    }
    // Freeze the target but for a rim along its edge, which is re-synthesized Free with the band
    // around the target (the pasted coordinates are its previous results): paste and surroundings
    // meet without a step.
    const std::vector<uint8_t> frozen = pasteTargetMask(paste, extent_);
    record(1, box.x - extent_.x, box.y - extent_.y, box.width, box.height);
    for (size_t i = 0; i < frozen.size(); ++i) frozen_[i] |= frozen[i];
    return resynthesize(growWindow(box, kCoherentBand), nullptr, params_.constraints, false);
}

Status IncrementalTerrain::removePaste(const Paste& paste, std::vector<uint8_t> frozen_after) {
    TERRASYNTH_REQUIRE(frozen_after.size() == frozen_.size(), "removePaste needs one frozen value per extent pixel");
    if (paste.source.size() < 3) return Status::error("paste: the source polygon needs at least 3 points");
    const auto target = targetPolygon(paste);
    const PixelWindow box = polygonBox(target, extent_);
    if (box.empty()) return Status::ok();
    // Forgotten coordinates offer no previous candidate: the Free re-synthesis starts afresh there.
    for (size_t level = 0; level < history_->levels.size(); ++level) {
        auto& l = history_->levels[level];
        if (l.width == 0) continue;
        forEachLevelPixelInside(l, static_cast<int>(level), target, [&](int x, int y, size_t i) {
            recordHistory(static_cast<int>(level), l.x + x, l.y + y, 1, 1);
            for (auto& pass : l.passes) pass.index[i] = synth::kNoPrevious;
        });
    }
    setFrozen(std::move(frozen_after));
    return resynthesize(growWindow(box, kCoherentBand), nullptr, params_.constraints, false);
}

// ---- Undo journal ----

IncrementalTerrain::Journal::Journal() = default;
IncrementalTerrain::Journal::Journal(Journal&&) noexcept = default;
IncrementalTerrain::Journal& IncrementalTerrain::Journal::operator=(Journal&&) noexcept = default;
IncrementalTerrain::Journal::~Journal() = default;
bool IncrementalTerrain::Journal::empty() const { return !tiles_ || tiles_->empty(); }
size_t IncrementalTerrain::Journal::bytes() const { return tiles_ ? tiles_->bytes() : 0; }
void IncrementalTerrain::Journal::absorb(Journal&& later) {
    if (!later.tiles_) return;
    if (!tiles_) tiles_ = std::move(later.tiles_);
    else tiles_->absorb(std::move(*later.tiles_));
}

void IncrementalTerrain::beginJournal() {
    if (!journal_) journal_ = std::make_unique<detail::TileJournal>();
}

IncrementalTerrain::Journal IncrementalTerrain::takeJournal() {
    Journal j;
    j.tiles_ = std::move(journal_);
    return j;
}

namespace {
constexpr int kFirstHistoryPlane = 2;
}  // namespace

void IncrementalTerrain::swapJournal(Journal& journal) {
    if (!journal.tiles_) return;
    // History planes are numbered with a fixed stride per level: levels record different pass counts.
    const int passes = synth::kMaxHistoryPassesPerLevel;
    journal.tiles_->swap([&](int id) -> detail::JournalPlane {
        if (id == 0) return {heights_.heights.data(), heights_.width, heights_.height, sizeof(float)};
        if (id == 1) return {frozen_.data(), extent_.width, extent_.height, 1};
        const int k = (id - kFirstHistoryPlane) / 2, level = k / passes, pass = k % passes;
        auto& l = history_->levels[level];
        if ((id - kFirstHistoryPlane) % 2 == 0) return {l.passes[pass].index.data(), l.width, l.height, sizeof(uint32_t)};
        return {l.passes[pass].v.data(), l.width, l.height, sizeof(float)};
    });
}

void IncrementalTerrain::record(int plane, int64_t x, int64_t y, int64_t w, int64_t h) {
    if (!journal_) return;
    if (plane == 0) journal_->record(0, {heights_.heights.data(), heights_.width, heights_.height, sizeof(float)}, x, y, w, h);
    else journal_->record(1, {frozen_.data(), extent_.width, extent_.height, 1}, x, y, w, h);
}

void IncrementalTerrain::recordHistory(int level, int64_t gx, int64_t gy, int64_t w, int64_t h) {
    if (!journal_) return;
    auto& l = history_->levels[level];
    const int passes = synth::kMaxHistoryPassesPerLevel;
    TERRASYNTH_REQUIRE(l.passes.size() <= static_cast<size_t>(passes), "more history passes than planes per level");
    for (int pass = 0; pass < static_cast<int>(l.passes.size()); ++pass) {
        const int id = kFirstHistoryPlane + 2 * (level * passes + pass);
        journal_->record(id, {l.passes[pass].index.data(), l.width, l.height, sizeof(uint32_t)}, gx - l.x, gy - l.y, w, h);
        journal_->record(id + 1, {l.passes[pass].v.data(), l.width, l.height, sizeof(float)}, gx - l.x, gy - l.y, w, h);
    }
}

}  // namespace terrasynth
