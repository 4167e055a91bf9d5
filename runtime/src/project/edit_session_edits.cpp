// EditSession: the edits. Each checks its input first (a Status naming the field), then runs as one
// Impl::edit: lists and planes change, the incremental terrain re-synthesizes the reach of what
// changed (s5.3), and on any error everything is put back.
#include <algorithm>
#include <cmath>

#include "constraints/type_paint.h"
#include "core/number_text.h"
#include "project/edit_session_impl.h"
#include "project/extent_build.h"

namespace terrasynth {
namespace {

using Stroke = std::vector<std::pair<double, double>>;

// The limits of the project file (constraints_json.cpp), so an edit never makes what cannot be saved.
constexpr double kMaxHeight = 12000.0, kMaxCoordinate = 1e8, kMaxGradient = 20.0, kMaxReach = 1e5;

Status inRange(const std::string& field, double v, double lo, double hi) {
    if (std::isfinite(v) && v >= lo && v <= hi) return Status::ok();
    return Status::error(field + ": must be in [" + detail::compactNumber(lo) + ", " + detail::compactNumber(hi) +
                         "], got " + detail::compactNumber(v));
}

Status checkSite(const std::string& field, double x, double y, const PixelWindow& extent) {
    if (Status s = inRange(field + ".x", x - extent.x, -kMaxCoordinate, kMaxCoordinate); !s) return s;
    return inRange(field + ".y", y - extent.y, -kMaxCoordinate, kMaxCoordinate);
}

Status checkPoint(const PointConstraint& p, const PixelWindow& extent) {
    for (Status s : {checkSite("point", p.x, p.y, extent), inRange("point.height_m", p.height_m, -kMaxHeight, kMaxHeight),
                     inRange("point.slope_direction_deg", p.slope_direction_deg, -360, 360),
                     inRange("point.slope_angle_deg", p.slope_angle_deg, 0, 80),
                     inRange("point.radius_px", p.radius_px, 1e-3, 1e6)})
        if (!s) return s;
    return Status::ok();
}

Status checkWidget(const std::string& field, const CurveWidget& w) {
    for (Status s : {inRange(field + ".t", w.t, 0, 1), inRange(field + ".height_m", w.height_m, -kMaxHeight, kMaxHeight),
                     inRange(field + ".left_gradient", w.left_gradient, -kMaxGradient, kMaxGradient),
                     inRange(field + ".right_gradient", w.right_gradient, -kMaxGradient, kMaxGradient),
                     inRange(field + ".left_reach_px", w.left_reach_px, 1e-3, kMaxReach),
                     inRange(field + ".right_reach_px", w.right_reach_px, 1e-3, kMaxReach)})
        if (!s) return s;
    return Status::ok();
}

Status checkCurve(const CurveConstraint& c, const PixelWindow& extent) {
    if (c.course.size() < 2) return Status::error("curve.course: needs at least 2 points");
    for (size_t i = 0; i < c.course.size(); ++i)
        if (Status s = checkSite("curve.course[" + std::to_string(i) + "]", c.course[i].first, c.course[i].second, extent); !s)
            return s;
    if (c.widgets.empty()) return Status::error("curve.widgets: needs at least one widget");
    for (size_t i = 0; i < c.widgets.size(); ++i) {
        if (Status s = checkWidget("curve.widgets[" + std::to_string(i) + "]", c.widgets[i]); !s) return s;
        if (i > 0 && c.widgets[i].t < c.widgets[i - 1].t)
            return Status::error("curve.widgets[" + std::to_string(i) + "].t: widgets must be sorted by t");
    }
    return Status::ok();
}

Status checkStroke(const Stroke& stroke, double radius, const PixelWindow& extent) {
    if (stroke.empty()) return Status::error("stroke: needs at least one point");
    if (Status s = inRange("stroke.radius_px", radius, 0.5, kMaxReach); !s) return s;
    for (size_t i = 0; i < stroke.size(); ++i)
        if (Status s = checkSite("stroke.points[" + std::to_string(i) + "]", stroke[i].first, stroke[i].second, extent); !s)
            return s;
    return Status::ok();
}

Status checkPaste(const PasteConstraint& p, const ExemplarDatabase& db, const PixelWindow& extent) {
    if (p.source.size() < 3) return Status::error("paste.source: needs at least 3 points");
    if (p.exemplar >= static_cast<int>(db.exemplars.size()) || p.exemplar < -1)
        return Status::error("paste.exemplar: " + std::to_string(p.exemplar) + " is not in the database");
    for (size_t i = 0; i < p.source.size(); ++i) {
        const std::string field = "paste.source[" + std::to_string(i) + "]";
        const double x = p.source[i].first, y = p.source[i].second;
        if (p.exemplar < 0) {
            if (Status s = checkSite(field, x, y, extent); !s) return s;
        } else if (Status s = checkSite(field, x + extent.x, y + extent.y, extent); !s) {
            return s;
        }
        if (Status s = checkSite("paste.target", x + p.dx, y + p.dy, extent); !s) return s;
    }
    return inRange("paste.height_offset_m", p.height_offset_m, -kMaxHeight, kMaxHeight);
}

template <class T>
Result<size_t> indexOf(const std::vector<EditId>& ids, EditId id, const char* what) {
    auto it = std::find(ids.begin(), ids.end(), id);
    if (it == ids.end()) return Status::error(std::string(what) + " " + std::to_string(id) + ": no such " + what);
    return static_cast<size_t>(it - ids.begin());
}

Status widgetIndex(const CurveConstraint& c, int index) {
    if (index < 0 || index >= static_cast<int>(c.widgets.size()))
        return Status::error("widget " + std::to_string(index) + ": out of range (the curve has " +
                             std::to_string(c.widgets.size()) + " widgets)");
    return Status::ok();
}

void insertSorted(std::vector<CurveWidget>& widgets, const CurveWidget& w) {
    auto at = std::upper_bound(widgets.begin(), widgets.end(), w.t, [](double t, const CurveWidget& o) { return t < o.t; });
    widgets.insert(at, w);
}

// The mask of one brush stroke over its box (clipped to the extent): 1 under the brush.
TypePaint strokeMask(const Stroke& stroke, double radius, const PixelWindow& extent) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (auto [x, y] : stroke) x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    const PixelWindow box = intersectWindows(
        {static_cast<int64_t>(std::floor(x0 - radius)), static_cast<int64_t>(std::floor(y0 - radius)),
         static_cast<int>(std::ceil(x1 - x0 + 2 * radius)) + 2, static_cast<int>(std::ceil(y1 - y0 + 2 * radius)) + 2},
        extent);
    TypePaint mask;
    mask.x = box.x, mask.y = box.y, mask.width = box.width, mask.height = box.height;
    mask.types.assign(static_cast<size_t>(std::max(0, box.width)) * std::max(0, box.height), 0);
    if (!box.empty()) paintStroke(mask, stroke, radius, 1);
    return mask;
}

}  // namespace

// ---- Points ----

Result<PixelWindow> EditSession::addPoint(const PointConstraint& point, EditId* id) {
    Impl& s = *impl_;
    if (Status c = checkPoint(point, s.extent); !c) return c;
    const EditId new_id = s.newId();
    auto changed = s.edit(true, false, [&] {
        PointConstraint p = point;
        p.takeLifts(PointConstraint());
        s.lists.points.push_back(p);
        s.lists.point_ids.push_back(new_id);
        return s.terrain->applyEdit(s.shaping());
    });
    if (changed && id) *id = new_id;
    return changed;
}

Result<PixelWindow> EditSession::setPoint(EditId id, const PointConstraint& point) {
    Impl& s = *impl_;
    auto i = indexOf<PointConstraint>(s.lists.point_ids, id, "point");
    if (!i) return i.status();
    if (Status c = checkPoint(point, s.extent); !c) return c;
    return s.edit(true, false, [&] {
        PointConstraint& p = s.lists.points[*i];
        const PointConstraint before = p;  // the search for the new lifts starts from the old ones
        p = point;
        p.takeLifts(before);
        return s.terrain->applyEdit(s.shaping());
    });
}

Result<PixelWindow> EditSession::movePoint(EditId id, double x, double y) {
    const PointConstraint* p = point(id);
    if (!p) return Status::error("point " + std::to_string(id) + ": no such point");
    PointConstraint moved = *p;
    moved.x = x, moved.y = y;
    return setPoint(id, moved);
}

Result<PixelWindow> EditSession::removePoint(EditId id) {
    Impl& s = *impl_;
    auto i = indexOf<PointConstraint>(s.lists.point_ids, id, "point");
    if (!i) return i.status();
    return s.edit(true, false, [&] {
        s.lists.points.erase(s.lists.points.begin() + static_cast<long>(*i));
        s.lists.point_ids.erase(s.lists.point_ids.begin() + static_cast<long>(*i));
        return s.terrain->applyEdit(s.shaping());
    });
}

// ---- Curves ----

Result<PixelWindow> EditSession::addCurve(const CurveConstraint& curve, EditId* id) {
    Impl& s = *impl_;
    if (Status c = checkCurve(curve, s.extent); !c) return c;
    const EditId new_id = s.newId();
    auto changed = s.edit(true, false, [&] {
        s.lists.curves.push_back(curve);
        s.lists.curve_ids.push_back(new_id);
        return s.terrain->applyEdit(s.shaping());
    });
    if (changed && id) *id = new_id;
    return changed;
}

Result<PixelWindow> EditSession::setCurve(EditId id, const CurveConstraint& curve) {
    Impl& s = *impl_;
    auto i = indexOf<CurveConstraint>(s.lists.curve_ids, id, "curve");
    if (!i) return i.status();
    if (Status c = checkCurve(curve, s.extent); !c) return c;
    return s.edit(true, false, [&] {
        s.lists.curves[*i] = curve;
        return s.terrain->applyEdit(s.shaping());
    });
}

Result<PixelWindow> EditSession::removeCurve(EditId id) {
    Impl& s = *impl_;
    auto i = indexOf<CurveConstraint>(s.lists.curve_ids, id, "curve");
    if (!i) return i.status();
    return s.edit(true, false, [&] {
        s.lists.curves.erase(s.lists.curves.begin() + static_cast<long>(*i));
        s.lists.curve_ids.erase(s.lists.curve_ids.begin() + static_cast<long>(*i));
        return s.terrain->applyEdit(s.shaping());
    });
}

Result<PixelWindow> EditSession::moveCoursePoint(EditId id, int index, double x, double y) {
    const CurveConstraint* c = curve(id);
    if (!c) return Status::error("curve " + std::to_string(id) + ": no such curve");
    if (index < 0 || index >= static_cast<int>(c->course.size()))
        return Status::error("course point " + std::to_string(index) + ": out of range (the course has " +
                             std::to_string(c->course.size()) + " points)");
    CurveConstraint moved = *c;
    moved.course[static_cast<size_t>(index)] = {x, y};
    return setCurve(id, moved);
}

Result<PixelWindow> EditSession::addWidget(EditId id, const CurveWidget& widget) {
    const CurveConstraint* c = curve(id);
    if (!c) return Status::error("curve " + std::to_string(id) + ": no such curve");
    CurveConstraint next = *c;
    insertSorted(next.widgets, widget);
    return setCurve(id, next);
}

Result<PixelWindow> EditSession::setWidget(EditId id, int index, const CurveWidget& widget) {
    const CurveConstraint* c = curve(id);
    if (!c) return Status::error("curve " + std::to_string(id) + ": no such curve");
    if (Status w = widgetIndex(*c, index); !w) return w;
    CurveConstraint next = *c;
    next.widgets.erase(next.widgets.begin() + index);
    insertSorted(next.widgets, widget);
    return setCurve(id, next);
}

Result<PixelWindow> EditSession::moveWidget(EditId id, int index, double t) {
    const CurveConstraint* c = curve(id);
    if (!c) return Status::error("curve " + std::to_string(id) + ": no such curve");
    if (Status w = widgetIndex(*c, index); !w) return w;
    CurveWidget moved = c->widgets[static_cast<size_t>(index)];
    moved.t = t;
    return setWidget(id, index, moved);
}

Result<PixelWindow> EditSession::removeWidget(EditId id, int index) {
    const CurveConstraint* c = curve(id);
    if (!c) return Status::error("curve " + std::to_string(id) + ": no such curve");
    if (Status w = widgetIndex(*c, index); !w) return w;
    if (c->widgets.size() == 1) return Status::error("widget 0: a curve keeps at least one widget (remove the curve)");
    CurveConstraint next = *c;
    next.widgets.erase(next.widgets.begin() + index);
    return setCurve(id, next);
}

// ---- Painting and freezing ----

Result<PixelWindow> EditSession::paintTypes(const Stroke& stroke, double radius_px, const std::string& type_name) {
    Impl& s = *impl_;
    if (Status c = checkStroke(stroke, radius_px, s.extent); !c) return c;
    const auto& names = s.db->type_names;
    auto it = std::find(names.begin(), names.end(), type_name);
    if (it == names.end()) return Status::error("type \"" + type_name + "\": not a type of the database");
    if (names.size() > static_cast<size_t>(kMaxPaintableTypes))
        return Status::error("type painting needs a database of at most 32 types");
    const uint8_t type = static_cast<uint8_t>(it - names.begin());
    return s.edit(false, false, [&] {
        s.paintPlane(Impl::kTypesPlane, stroke, radius_px, type);
        return s.terrain->applyEdit(s.shaping());
    });
}

Result<PixelWindow> EditSession::eraseTypes(const Stroke& stroke, double radius_px) {
    Impl& s = *impl_;
    if (Status c = checkStroke(stroke, radius_px, s.extent); !c) return c;
    return s.edit(false, false, [&] {
        s.paintPlane(Impl::kTypesPlane, stroke, radius_px, TypePaint::kUnpainted);
        return s.terrain->applyEdit(s.shaping());
    });
}

Result<PixelWindow> EditSession::freeze(const Stroke& stroke, double radius_px) {
    Impl& s = *impl_;
    if (Status c = checkStroke(stroke, radius_px, s.extent); !c) return c;
    return s.edit(false, false, [&] {
        s.paintPlane(Impl::kFreezePlane, stroke, radius_px, 1);
        s.terrain->freeze(strokeMask(stroke, radius_px, s.extent));
        return Status::ok();
    });
}

Result<PixelWindow> EditSession::unfreeze(const Stroke& stroke, double radius_px) {
    Impl& s = *impl_;
    if (Status c = checkStroke(stroke, radius_px, s.extent); !c) return c;
    return s.edit(false, false, [&] {
        s.paintPlane(Impl::kFreezePlane, stroke, radius_px, 0);
        s.terrain->setFrozen(s.frozenMask());  // pasted pixels stay frozen
        return Status::ok();
    });
}

// ---- Pastes ----

Result<PixelWindow> EditSession::addPaste(const PasteConstraint& paste, EditId* id) {
    Impl& s = *impl_;
    if (Status c = checkPaste(paste, *s.db, s.extent); !c) return c;
    const EditId new_id = s.newId();
    auto changed = s.edit(true, false, [&] {
        s.lists.pastes.push_back(paste);
        s.lists.paste_ids.push_back(new_id);
        return s.terrain->paste(paste);
    });
    if (changed && id) *id = new_id;
    return changed;
}

Result<PixelWindow> EditSession::removePaste(EditId id) {
    Impl& s = *impl_;
    auto i = indexOf<PasteConstraint>(s.lists.paste_ids, id, "paste");
    if (!i) return i.status();
    return s.edit(true, false, [&] {
        const PasteConstraint removed = s.lists.pastes[*i];
        std::vector<uint8_t> frozen_after = s.frozenMask({*i});
        s.lists.pastes.erase(s.lists.pastes.begin() + static_cast<long>(*i));
        s.lists.paste_ids.erase(s.lists.paste_ids.begin() + static_cast<long>(*i));
        return s.terrain->removePaste(removed, std::move(frozen_after));
    });
}

// ---- Any constraints at once ----

Result<PixelWindow> EditSession::setConstraints(const SynthesisConstraints& next) {
    Impl& s = *impl_;
    for (size_t i = 0; i < next.points.size(); ++i)
        if (Status c = checkPoint(next.points[i], s.extent); !c) return c.withContext("points[" + std::to_string(i) + "]");
    for (size_t i = 0; i < next.curves.size(); ++i)
        if (Status c = checkCurve(next.curves[i], s.extent); !c) return c.withContext("curves[" + std::to_string(i) + "]");
    std::vector<uint8_t> next_freeze = constraints::paintOnWindow(next.freeze, s.extent, 0);
    for (uint8_t& v : next_freeze) v = v != 0 && v != TypePaint::kUnpainted ? 1 : 0;
    bool same_pastes = next.pastes.size() == s.lists.pastes.size();
    for (size_t i = 0; i < next.pastes.size() && same_pastes; ++i) {
        const PasteConstraint &a = next.pastes[i], &b = s.lists.pastes[i];
        same_pastes = a.source == b.source && a.exemplar == b.exemplar && a.dx == b.dx && a.dy == b.dy &&
                      a.height_offset_m == b.height_offset_m;
    }
    if (!same_pastes) return Status::error("constraints.pastes: differ; use addPaste() and removePaste()");
    std::vector<uint8_t> next_types = next.types.empty() ? std::vector<uint8_t>(s.types.types.size(), TypePaint::kUnpainted)
                                                         : constraints::paintOnWindow(next.types, s.extent, TypePaint::kUnpainted);
    for (uint8_t t : next_types)
        if (t != TypePaint::kUnpainted && t >= s.db->type_names.size())
            return Status::error("constraints.types: type id " + std::to_string(t) + " is not in the database");
    return s.edit(true, false, [&] {
        // Points and curves the edit left alone keep their ids and lifts, so only the edited ones
        // count as changed (s5.3: W = 1 inside the manipulated constraints' reach only).
        EditLists lists;
        std::vector<bool> taken(s.lists.points.size(), false);
        for (const PointConstraint& p : next.points) {
            PointConstraint q = p;
            q.takeLifts(PointConstraint());
            EditId id = 0;
            for (size_t k = 0; k < s.lists.points.size() && !id; ++k)
                if (!taken[k] && s.lists.points[k].samePlacement(p)) taken[k] = true, q.takeLifts(s.lists.points[k]),
                                                                     id = s.lists.point_ids[k];
            lists.points.push_back(q);
            lists.point_ids.push_back(id ? id : s.newId());
        }
        for (const CurveConstraint& c : next.curves) {
            EditId id = 0;
            for (size_t k = 0; k < s.lists.curves.size() && !id; ++k)
                if (s.lists.curves[k].course == c.course && s.lists.curves[k].spline == c.spline &&
                    std::find(lists.curve_ids.begin(), lists.curve_ids.end(), s.lists.curve_ids[k]) == lists.curve_ids.end())
                    id = s.lists.curve_ids[k];
            lists.curves.push_back(c);
            lists.curve_ids.push_back(id ? id : s.newId());
        }
        lists.pastes = s.lists.pastes;
        lists.paste_ids = s.lists.paste_ids;
        s.lists = std::move(lists);
        // The freeze brush first, so the pixels it newly covers hold through the edit.
        if (next_freeze != s.freeze_brush.types) {
            s.planes_journal->record(Impl::kFreezePlane, {s.freeze_brush.types.data(), s.freeze_brush.width,
                                                          s.freeze_brush.height, 1},
                                     0, 0, s.freeze_brush.width, s.freeze_brush.height);
            s.freeze_brush.types = next_freeze;
            s.terrain->setFrozen(s.frozenMask());
        }
        if (next_types != s.types.types) {
            s.planes_journal->record(Impl::kTypesPlane, {s.types.types.data(), s.types.width, s.types.height, 1}, 0, 0,
                                     s.types.width, s.types.height);
            s.types.types = next_types;
        }
        return s.terrain->applyEdit(s.shaping());
    });
}

Result<PixelWindow> EditSession::setLayers(LayerStack stack) {
    return impl_->edit(false, true, [&] { return impl_->layers->setStack(std::move(stack)); });
}

// ---- Re-seeding ----

Result<PixelWindow> EditSession::reseed(uint32_t seed) {
    Impl& s = *impl_;
    if (s.gesture_depth > 0) return Status::error("reseed: not inside a gesture");
    EditStep step;
    step.lists = s.lists;
    step.seed = std::make_unique<SeedState>();
    step.seed->seed = s.seed;
    step.seed->world = s.world;
    step.seed->reference0 = s.reference0;
    Project project = s.project;
    project.synthesis.seed = seed;
    auto built = [&]() -> Status {
        auto reference = project::referenceParams(*s.synthesizer, project,
                                                  std::make_shared<const SynthesisConstraints>(s.fullConstraints()));
        if (!reference) return reference.status();
        auto terrain = project::buildIncrementalExtent(*s.synthesizer, s.extent, reference.value(),
                                                       project.hold_point_heights, project.path);
        if (!terrain) return terrain.status();
        auto plain = s.synthesizer->synthesize(s.extent, reference.value(), 0, false);
        if (!plain) return plain.status();
        step.seed->terrain = std::move(s.terrain);
        s.terrain = std::move(terrain.value());
        s.reference0 = std::make_shared<const std::vector<float>>(std::move(plain->heights.heights));
        s.world = std::make_shared<const project::WorldView>(s.pool, reference.value());
        s.seed = seed;
        s.project.synthesis.seed = seed;
        return Status::ok();
    }();
    if (!built) {
        s.world = step.seed->world;
        s.reference0 = step.seed->reference0;
        return built;
    }
    s.syncLifts();
    return s.finish(std::move(step));
}

// ---- Layers ----

Result<PixelWindow> EditSession::addLayer(EditLayer layer, int index) {
    return impl_->edit(false, true, [&] { return impl_->layers->addLayer(std::move(layer), index); });
}
Result<PixelWindow> EditSession::removeLayer(int index) {
    return impl_->edit(false, true, [&] { return impl_->layers->removeLayer(index); });
}
Result<PixelWindow> EditSession::moveLayer(int from, int to) {
    return impl_->edit(false, true, [&] { return impl_->layers->moveLayer(from, to); });
}
Result<PixelWindow> EditSession::setLayerVisible(int index, bool visible) {
    return impl_->edit(false, true, [&] { return impl_->layers->setVisible(index, visible); });
}
Result<PixelWindow> EditSession::setLayerWeights(int index, BandWeights weights) {
    return impl_->edit(false, true, [&] { return impl_->layers->setWeights(index, weights); });
}
Result<PixelWindow> EditSession::setBaseWeights(BandWeights weights) {
    return impl_->edit(false, true, [&] { return impl_->layers->setBaseWeights(weights); });
}
Result<PixelWindow> EditSession::replaceLayer(int index, EditLayer layer) {
    return impl_->edit(false, true, [&] { return impl_->layers->replaceLayer(index, std::move(layer)); });
}
Result<PixelWindow> EditSession::setLayerBase(BaseLayer base) {
    return impl_->edit(false, true, [&] { return impl_->layers->setBase(std::move(base)); });
}
Result<PixelWindow> EditSession::setBandSplit(BandSplit split) {
    return impl_->edit(false, true, [&] { return impl_->layers->setBandSplit(split); });
}
Result<PixelWindow> EditSession::mergeLayerDown(int index) {
    return impl_->edit(false, true, [&] { return impl_->layers->mergeDown(index); });
}
Result<std::vector<Heightfield>> EditSession::holeFillPreviews(int index, int generation) {
    if (Status s = impl_->layers->setSynthesizedTerrain(impl_->terrain->heights()); !s) return s;
    return impl_->layers->holeFillPreviews(index, generation);
}

}  // namespace terrasynth
