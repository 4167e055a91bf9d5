// EditSession: opening, state, snapshots, undo and redo. The edits themselves are in
// edit_session_edits.cpp, saving and the sidecar in edit_session_save.cpp.
#include "terrasynth/edit_session.h"

#include <algorithm>
#include <cmath>

#include "constraints/type_paint.h"
#include "core/paths.h"
#include "project/edit_session_impl.h"
#include "project/extent_build.h"

namespace terrasynth {

// ---- Steps ----

size_t EditStep::bytes() const {
    size_t n = terrain.bytes() + planes.bytes();
    if (lists) {
        n += lists->points.size() * sizeof(PointConstraint) + lists->pastes.size() * sizeof(PasteConstraint);
        for (const CurveConstraint& c : lists->curves) n += c.course.size() * 16 + c.widgets.size() * sizeof(CurveWidget);
    }
    if (seed && seed->terrain) {
        n += seed->terrain->heights().size() * sizeof(float) + seed->terrain->history().memoryBytes() +
             seed->terrain->frozenMask().size();
        if (seed->reference0) n += seed->reference0->size() * sizeof(float);
    }
    return n;
}

void EditStep::absorb(EditStep&& later) {
    terrain.absorb(std::move(later.terrain));
    planes.absorb(std::move(later.planes));
    if (!lists) lists = std::move(later.lists);
    if (!stack) stack = std::move(later.stack);
    if (!seed) seed = std::move(later.seed);
}

// ---- State ----

bool EditSession::Impl::anyPainted() const {
    return std::any_of(types.types.begin(), types.types.end(), [](uint8_t t) { return t != TypePaint::kUnpainted; });
}

SynthesisConstraints EditSession::Impl::fullConstraints() const {
    SynthesisConstraints c;
    c.points = lists.points;
    c.curves = lists.curves;
    c.pastes = lists.pastes;
    if (anyPainted()) c.types = types;
    if (std::any_of(freeze_brush.types.begin(), freeze_brush.types.end(), [](uint8_t v) { return v != 0; }))
        c.freeze = freeze_brush;
    return c;
}

std::shared_ptr<const SynthesisConstraints> EditSession::Impl::shaping() const {
    const bool painted = anyPainted();
    if (lists.points.empty() && lists.curves.empty() && !painted) return nullptr;
    auto c = std::make_shared<SynthesisConstraints>();
    c->points = lists.points;
    c->curves = lists.curves;
    if (painted) c->types = types;
    return c;
}

void EditSession::Impl::syncLifts() {
    const auto& current = terrain->params().constraints;
    if (!current) return;
    if (current->points.size() == lists.points.size())
        for (size_t i = 0; i < lists.points.size(); ++i) lists.points[i].takeLifts(current->points[i]);
    if (current->curves.size() == lists.curves.size())
        for (size_t i = 0; i < lists.curves.size(); ++i) lists.curves[i].lift_m = current->curves[i].lift_m;
}

Status EditSession::Impl::restoreTerrainConstraints() {
    terrain->restoreConstraints(shaping());
    return Status::ok();
}

std::vector<uint8_t> EditSession::Impl::frozenMask(const std::vector<size_t>& skip_pastes) const {
    std::vector<uint8_t> mask(freeze_brush.types.size());
    for (size_t i = 0; i < mask.size(); ++i) mask[i] = freeze_brush.types[i] ? 1 : 0;
    for (size_t k = 0; k < lists.pastes.size(); ++k) {
        if (std::find(skip_pastes.begin(), skip_pastes.end(), k) != skip_pastes.end()) continue;
        const std::vector<uint8_t> covered = pasteTargetMask(lists.pastes[k], extent);
        for (size_t i = 0; i < mask.size(); ++i) mask[i] |= covered[i];
    }
    return mask;
}

void EditSession::Impl::paintPlane(int id, const std::vector<std::pair<double, double>>& stroke, double radius,
                                   uint8_t value) {
    TypePaint& p = plane(id);
    if (planes_journal) {
        // The stroke's box, clipped by the journal.
        double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
        for (auto [x, y] : stroke) x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
        const double lo = -1e12, hi = 1e12;
        const int64_t bx = static_cast<int64_t>(std::clamp(std::floor(x0 - radius), lo, hi)) - p.x;
        const int64_t by = static_cast<int64_t>(std::clamp(std::floor(y0 - radius), lo, hi)) - p.y;
        const int64_t bw = static_cast<int64_t>(std::clamp(std::ceil(x1 + radius), lo, hi)) - p.x - bx + 1;
        const int64_t bh = static_cast<int64_t>(std::clamp(std::ceil(y1 + radius), lo, hi)) - p.y - by + 1;
        planes_journal->record(id, {p.types.data(), p.width, p.height, 1}, bx, by, bw, bh);
    }
    paintStroke(p, stroke, radius, value);
}

namespace {
bool isIdentity(const LayerStack& stack) {
    return stack.layers.empty() && stack.base.source == BaseSource::Synthesized && stack.base.weights == BandWeights{};
}
}  // namespace

Status EditSession::Impl::compose() {
    const Heightfield& base = terrain->heights();
    if (isIdentity(layers->stack())) {
        heights = base;
        return Status::ok();
    }
    if (Status s = layers->setSynthesizedTerrain(base); !s) return s;
    auto composed = layers->currentHeights();
    if (!composed) return composed.status();
    heights = **composed;
    return Status::ok();
}

PixelWindow EditSession::Impl::publish() {
    auto previous = std::atomic_load(&snapshot);
    auto now = std::make_shared<const std::vector<float>>(heights.heights);
    const bool same_world = previous && previous->world == world && previous->edit->referencePtr() == reference0;
    const PixelWindow changed = same_world ? differingWindow(extent, previous->edit->heights(), *now) : extent;
    auto next = std::make_shared<SessionSnapshot>();
    next->world = world;
    next->edit = same_world ? std::make_shared<const project::ExtentEdit>(extent, std::move(now), reference0,
                                                                          *previous->edit, changed)
                            : std::make_shared<const project::ExtentEdit>(extent, std::move(now), reference0);
    std::atomic_store(&snapshot, std::shared_ptr<const SessionSnapshot>(std::move(next)));
    return changed;
}

void EditSession::Impl::swapStep(EditStep& step) {
    if (step.seed) {
        std::swap(seed, step.seed->seed);
        std::swap(terrain, step.seed->terrain);
        std::swap(world, step.seed->world);
        std::swap(reference0, step.seed->reference0);
        project.synthesis.seed = seed;
    }
    terrain->swapJournal(step.terrain);
    step.planes.swap([this](int id) -> detail::JournalPlane {
        TypePaint& p = plane(id);
        return {p.types.data(), p.width, p.height, 1};
    });
    if (step.lists) std::swap(lists, *step.lists);
    if (step.stack) {
        LayerStack now = layers->stack();
        Status s = layers->setStack(std::move(*step.stack));
        TERRASYNTH_REQUIRE(s.isOk(), "a layer stack the session held must validate");
        step.stack = std::move(now);
    }
    restoreTerrainConstraints();
}

void EditSession::Impl::pushStep(EditStep step) {
    if (gesture_depth > 0) {
        if (gesture) gesture->absorb(std::move(step));
        else gesture = std::move(step);
        return;
    }
    undo.push_back(std::move(step));
    redo.clear();
    const size_t limit = static_cast<size_t>(std::clamp(options.max_undo_steps, 1, 256));
    while (undo.size() > limit) undo.erase(undo.begin());
    // The byte budget: a re-synthesis of a large extent journals hundreds of MB, so the count alone
    // would let a day of edits hold tens of GB. The newest step always stays undoable.
    size_t held = 0;
    for (const EditStep& kept : undo) held += kept.bytes();
    while (undo.size() > 1 && held > options.max_undo_bytes) {
        held -= undo.front().bytes();
        undo.erase(undo.begin());
    }
}

Result<PixelWindow> EditSession::Impl::finish(EditStep step) {
    if (Status s = compose(); !s) {
        swapStep(step);
        if (Status back = compose(); !back) return back.withContext("restoring after a failed edit");
        return s;
    }
    const PixelWindow changed = publish();
    ++edit_count;
    pushStep(std::move(step));
    return changed;
}

const Project& EditSession::Impl::view() const {
    const uint64_t now = edit_count.load();
    if (view_at == now) return view_cache;
    view_cache = project;
    const SynthesisConstraints c = fullConstraints();
    auto written = constraintsToJson(c, *db, extent.x, extent.y, extent.width, extent.height, maskStem(project.path));
    if (written) view_cache.constraints_json = written->json;
    view_cache.layers_json = layerStackToJson(layers->stack());
    view_cache.synthesis.seed = seed;
    view_cache.synthesis.constraints = shaping();
    view_at = now;
    return view_cache;
}

// ---- Opening ----

EditSession::EditSession(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
EditSession::~EditSession() = default;

Result<std::unique_ptr<EditSession>> EditSession::open(const std::string& project_path, const EditSessionOptions& options) {
    auto project = loadProject(project_path);
    if (!project) return project.status();
    return fromProject(std::move(project.value()), options);
}

namespace {

// The lists and planes of parsed project constraints, with fresh ids.
void adoptConstraints(EditSession::Impl& s, const SynthesisConstraints* c) {
    s.types = TypePaint{};
    s.types.x = s.extent.x, s.types.y = s.extent.y, s.types.width = s.extent.width, s.types.height = s.extent.height;
    s.types.types.assign(static_cast<size_t>(s.extent.width) * s.extent.height, TypePaint::kUnpainted);
    s.freeze_brush = s.types;
    std::fill(s.freeze_brush.types.begin(), s.freeze_brush.types.end(), 0);
    s.lists = EditLists{};
    if (!c) return;
    s.lists.points = c->points;
    s.lists.curves = c->curves;
    s.lists.pastes = c->pastes;
    for (size_t i = 0; i < c->points.size(); ++i) s.lists.point_ids.push_back(s.newId());
    for (size_t i = 0; i < c->curves.size(); ++i) s.lists.curve_ids.push_back(s.newId());
    for (size_t i = 0; i < c->pastes.size(); ++i) s.lists.paste_ids.push_back(s.newId());
    if (!c->types.empty()) s.types.types = constraints::paintOnWindow(c->types, s.extent, TypePaint::kUnpainted);
    if (!c->freeze.empty()) s.freeze_brush.types = constraints::paintOnWindow(c->freeze, s.extent, 0);
}

}  // namespace

Result<std::unique_ptr<EditSession>> EditSession::fromProject(Project project, const EditSessionOptions& options) {
    auto impl = std::make_unique<Impl>();
    Impl& s = *impl;
    s.options = options;
    auto stack = parseLayerStack(project.layers_json, project.folder());
    if (!stack) return stack.status().withContext(project.path);
    if (options.preloaded_database) {
        s.db = options.preloaded_database;
    } else {
        auto db = openProjectDatabase(project, options.database);
        if (!db) return db.status();
        s.db = db.value();
    }
    auto constraints = project::projectConstraints(project, *s.db);
    if (!constraints) return constraints.status();
    s.pool = std::make_shared<project::SynthesizerPool>(s.db, options.synthesizer);
    auto synthesizer = s.pool->createPrivate();
    if (!synthesizer) return synthesizer.status();
    s.synthesizer = std::move(synthesizer.value());
    s.extent = {project.origin_x, project.origin_y, project.width, project.height};
    s.seed = project.synthesis.seed;
    s.project = std::move(project);
    adoptConstraints(s, constraints->get());
    bool restored = false;
    if (!s.project.edited_heights.empty()) {
        auto adopted = s.adoptSidecar();
        if (!adopted) return adopted.status();
        restored = adopted.value();
    }
    if (!restored) {
        // Afresh, exactly as Terrain makes the extent.
        auto reference = project::referenceParams(*s.synthesizer, s.project, constraints.value());
        if (!reference) return reference.status();
        auto built = project::buildIncrementalExtent(*s.synthesizer, s.extent, reference.value(),
                                                     s.project.hold_point_heights, s.project.path);
        if (!built) return built.status();
        s.terrain = std::move(built.value());
        if (project::needsIncrementalBuild(reference->constraints.get())) {
            auto plain = s.synthesizer->synthesize(s.extent, reference.value(), 0, false);
            if (!plain) return plain.status();
            s.reference0 = std::make_shared<const std::vector<float>>(std::move(plain->heights.heights));
        } else {
            s.reference0 = std::make_shared<const std::vector<float>>(s.terrain->heights().heights);
        }
        s.world = std::make_shared<const project::WorldView>(s.pool, reference.value());
        s.syncLifts();
    }
    auto editor = LayerEditor::create(std::move(stack.value()), s.terrain->heights());
    if (!editor) return editor.status().withContext(s.project.path);
    s.layers.emplace(std::move(editor.value()));
    if (Status c = s.compose(); !c) return c.withContext(s.project.path);
    s.publish();
    return std::unique_ptr<EditSession>(new EditSession(std::move(impl)));
}

// ---- Accessors ----

const Project& EditSession::project() const { return impl_->view(); }
const ExemplarDatabase& EditSession::database() const { return *impl_->db; }
std::shared_ptr<const ExemplarDatabase> EditSession::databasePtr() const { return impl_->db; }
PixelWindow EditSession::extent() const { return impl_->extent; }
GridFrame EditSession::frame() const { return {impl_->db->meters_per_pixel}; }
const Heightfield& EditSession::heights() const { return impl_->heights; }
const SynthesisConstraints& EditSession::constraints() const {
    const uint64_t now = impl_->edit_count.load();
    if (impl_->constraints_at != now) {
        impl_->constraints_cache = impl_->fullConstraints();
        impl_->constraints_at = now;
    }
    return impl_->constraints_cache;
}
const LayerStack& EditSession::layers() const { return impl_->layers->stack(); }
std::vector<EditId> EditSession::pointIds() const { return impl_->lists.point_ids; }
std::vector<EditId> EditSession::curveIds() const { return impl_->lists.curve_ids; }
std::vector<EditId> EditSession::pasteIds() const { return impl_->lists.paste_ids; }
const std::vector<std::string>& EditSession::warnings() const { return impl_->warnings; }

namespace {
template <class T>
const T* byId(const std::vector<T>& items, const std::vector<EditId>& ids, EditId id) {
    auto it = std::find(ids.begin(), ids.end(), id);
    return it == ids.end() ? nullptr : &items[static_cast<size_t>(it - ids.begin())];
}
}  // namespace

const PointConstraint* EditSession::point(EditId id) const { return byId(impl_->lists.points, impl_->lists.point_ids, id); }
const CurveConstraint* EditSession::curve(EditId id) const { return byId(impl_->lists.curves, impl_->lists.curve_ids, id); }
const PasteConstraint* EditSession::paste(EditId id) const { return byId(impl_->lists.pastes, impl_->lists.paste_ids, id); }

// ---- Undo ----

void EditSession::deferLifts(bool defer) {
    // Set on every gesture: a re-seed replaces the terrain object.
    impl_->terrain->setPreviewLevels(impl_->drag_preview_levels);
    impl_->terrain->deferLifts(defer);
}

Result<PixelWindow> EditSession::liftDeferred() {
    Impl& s = *impl_;
    s.terrain->deferLifts(false);
    if (!s.terrain->liftsPending()) return PixelWindow{};
    return s.edit(true, false, [&] { return s.terrain->liftDeferred(); });
}

void EditSession::setDragPreviewLevels(int levels) {
    TERRASYNTH_REQUIRE(levels >= 0 && levels <= 2, "setDragPreviewLevels takes 0..2 levels");
    impl_->drag_preview_levels = levels;
}

void EditSession::beginGesture() { ++impl_->gesture_depth; }

void EditSession::endGesture() {
    Impl& s = *impl_;
    TERRASYNTH_REQUIRE(s.gesture_depth > 0, "endGesture without beginGesture");
    if (--s.gesture_depth > 0 || !s.gesture) return;
    EditStep step = std::move(*s.gesture);
    s.gesture.reset();
    s.pushStep(std::move(step));
}

bool EditSession::canUndo() const { return !impl_->undo.empty(); }
bool EditSession::canRedo() const { return !impl_->redo.empty(); }

size_t EditSession::undoBytes() const {
    size_t n = impl_->gesture ? impl_->gesture->bytes() : 0;
    for (const auto* list : {&impl_->undo, &impl_->redo})
        for (const EditStep& step : *list) n += step.bytes();
    return n;
}

namespace {
Result<PixelWindow> replay(EditSession::Impl& s, std::vector<EditStep>& from, std::vector<EditStep>& to) {
    if (s.gesture_depth > 0) return Status::error("undo/redo: a gesture is in progress (call endGesture first)");
    if (from.empty()) return PixelWindow{s.extent.x, s.extent.y, 0, 0};
    EditStep step = std::move(from.back());
    from.pop_back();
    s.swapStep(step);
    if (Status c = s.compose(); !c) return c.withContext("undo/redo");
    const PixelWindow changed = s.publish();
    ++s.edit_count;
    to.push_back(std::move(step));
    return changed;
}
}  // namespace

Result<PixelWindow> EditSession::undo() { return replay(*impl_, impl_->undo, impl_->redo); }
Result<PixelWindow> EditSession::redo() { return replay(*impl_, impl_->redo, impl_->undo); }

// ---- Reading the world ----

HeightSource EditSession::heightSource() const {
    std::shared_ptr<const SessionSnapshot> snap = std::atomic_load(&impl_->snapshot);
    return [snap](const PixelWindow& window, int level) { return snap->world->heights(window, level, snap->edit.get()); };
}

Status EditSession::prepareThisThread() const { return impl_->pool->prepareThisThread(); }

Result<std::vector<double>> EditSession::heightsAt(const std::vector<std::array<double, 2>>& points) const {
    std::shared_ptr<const SessionSnapshot> snap = std::atomic_load(&impl_->snapshot);
    const GridFrame grid = frame();
    std::vector<double> out;
    out.reserve(points.size());
    for (const auto& p : points) {
        auto h = snap->world->heightAt(grid.pixelX(p[0]), grid.pixelY(p[1]), snap->edit.get());
        if (!h) return h.status();
        out.push_back(h.value());
    }
    return out;
}

Result<double> EditSession::heightAt(double world_x, double world_y) const {
    std::shared_ptr<const SessionSnapshot> snap = std::atomic_load(&impl_->snapshot);
    const GridFrame grid = frame();
    return snap->world->heightAt(grid.pixelX(world_x), grid.pixelY(world_y), snap->edit.get());
}

uint64_t EditSession::editCount() const { return impl_->edit_count.load(); }
bool EditSession::isDirty() const { return impl_->edit_count.load() != impl_->saved_at.load(); }

}  // namespace terrasynth
