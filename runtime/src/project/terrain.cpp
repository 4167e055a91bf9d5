// Terrain: a project ready for height queries. Synthesis is a pure function of the global pixel
// (windowed). What changes the extent beyond one synthesis (freeze and pastes, s5.3; the layer stack
// of Bradbury et al. 2014; an edit session's saved heights) is computed once, on first need, as an
// ExtentEdit over the reference synthesis (project/world_view.h): the same definition an edit
// session's snapshots use.
#include "terrasynth/terrain.h"

#include <cmath>
#include <mutex>

#include "project/constraints_json.h"
#include "project/edit_sidecar.h"
#include "project/extent_build.h"
#include "project/world_view.h"
#include "terrasynth/layers.h"

namespace terrasynth {

struct Terrain::Impl {
    Project project;
    TerrainOptions options;
    std::shared_ptr<project::SynthesizerPool> pool;
    std::unique_ptr<project::WorldView> world;
    // Set when the sidecar was accepted: the synthesized extent before the layer stack.
    std::shared_ptr<const std::vector<float>> saved_base;
    std::vector<std::string> warnings;

    std::mutex edit_mutex;
    bool edit_ready = false;
    std::shared_ptr<const project::ExtentEdit> edit;  // null: the extent is the reference synthesis

    void warn(const std::string& message) {
        warnings.push_back(message);
        if (options.on_warning) options.on_warning(message);
    }
    bool hasExtentEdit() const {
        return saved_base || project.hasLayers() || project::needsIncrementalBuild(project.synthesis.constraints.get());
    }
    Result<const project::ExtentEdit*> extentEdit();
    Status adoptSidecar(Synthesizer& synthesizer);
};

Terrain::Terrain(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Terrain::~Terrain() = default;

Result<std::shared_ptr<Terrain>> Terrain::open(const std::string& project_path, const TerrainOptions& options) {
    auto project = loadProject(project_path);
    if (!project) return project.status();
    return fromProject(std::move(project.value()), options);
}

Result<std::shared_ptr<Terrain>> Terrain::fromProject(Project project, const TerrainOptions& options) {
    if (Status s = checkProjectExtent(project); !s) return s.withContext(project.path);
    if (project.hasLayers()) {
        auto stack = parseLayerStack(project.layers_json, project.folder());
        if (!stack) return stack.status().withContext(project.path);
    }
    auto db = openProjectDatabase(project, options.database);
    if (!db) return db.status();
    auto constraints = project::projectConstraints(project, *db.value());
    if (!constraints) return constraints.status();
    auto impl = std::make_unique<Impl>();
    impl->options = options;
    impl->pool = std::make_shared<project::SynthesizerPool>(db.value(), options.synthesizer);
    // Fail early (missing OpenCL device, kernel build) rather than on the first tile.
    auto synthesizer = impl->pool->forThisThread();
    if (!synthesizer) return synthesizer.status();
    impl->project = std::move(project);
    impl->project.synthesis.constraints = constraints.value();
    if (!impl->project.edited_heights.empty())
        if (Status s = impl->adoptSidecar(*synthesizer.value()); !s) return s;
    if (!impl->world) {
        // Lifted once here, so every window and tile synthesizes with the same targets.
        auto reference = project::referenceParams(*synthesizer.value(), impl->project, constraints.value());
        if (!reference) return reference.status();
        impl->project.synthesis.constraints = reference->constraints;
        impl->world = std::make_unique<project::WorldView>(impl->pool, reference.value());
    }
    return std::shared_ptr<Terrain>(new Terrain(std::move(impl)));
}

// The sidecar an edit session saved: its heights replace the fresh synthesis while its digest matches
// the project; a missing, unreadable or stale one is a warning and the project is synthesized afresh.
Status Terrain::Impl::adoptSidecar(Synthesizer& synthesizer) {
    const std::string& path = project.edited_heights;
    const ExemplarDatabase& db = pool->database();
    auto reject = [&](const std::string& why) {
        warn(project.path + ": edited heights " + path + " " + why + "; synthesizing the project afresh");
        return Status::ok();
    };
    auto bytes = readFileBytes(path);
    if (!bytes) return reject("cannot be read (" + bytes.message() + ")");
    auto digest = project::projectEditDigest(project, db);
    if (!digest) return digest.status().withContext(project.path);
    auto stored = project::sidecarDigest(*bytes, path);
    if (!stored) return reject("are unusable (" + stored.message() + ")");
    if (*stored != *digest) return reject("belong to another version of the project (digest mismatch)");
    auto sidecar = project::decodeEditSidecar(*bytes, path, /*with_history=*/false);
    if (!sidecar) return reject("are unusable (" + sidecar.message() + ")");
    const PixelWindow extent{project.origin_x, project.origin_y, project.width, project.height};
    if (sidecar->extent != extent) return reject("cover another extent");
    auto reference = project::parseConstraintsJson(nlohmann::json::parse(sidecar->reference.json), project::masksFrom(sidecar->reference),
                                                 db, extent.x, extent.y, extent.width, extent.height);
    if (!reference) return reject("hold an unreadable reference (" + reference.message() + ")");
    // The project's points and curves as the session left them (their lifts), and the reference it
    // synthesized the world around the extent with.
    auto& current = project.synthesis.constraints;
    auto lifted = std::make_shared<SynthesisConstraints>(current ? *current : SynthesisConstraints());
    if (!project::applyLifts(sidecar->lifts, lifted->points, lifted->curves) ||
        !project::applyLifts(sidecar->reference_lifts, reference->points, reference->curves))
        return reject("hold lifts for other points or curves");
    if (current) current = lifted;
    SynthesisParams params = project::synthesisOf(project);
    params.constraints.reset();
    if (!reference->empty()) params.constraints = std::make_shared<const SynthesisConstraints>(std::move(reference.value()));
    world = std::make_unique<project::WorldView>(pool, params);
    saved_base = std::make_shared<const std::vector<float>>(std::move(sidecar->heights));
    (void)synthesizer;
    return Status::ok();
}

const Project& Terrain::project() const { return impl_->project; }
const ExemplarDatabase& Terrain::database() const { return impl_->pool->database(); }
std::shared_ptr<const ExemplarDatabase> Terrain::databasePtr() const { return impl_->pool->databasePtr(); }
double Terrain::metersPerPixel(int level) const { return database().meters_per_pixel * std::ldexp(1.0, level); }
PixelWindow Terrain::extent() const {
    const Project& p = impl_->project;
    return {p.origin_x, p.origin_y, p.width, p.height};
}
bool Terrain::usesEditedHeights() const { return impl_->saved_base != nullptr; }
std::vector<std::string> Terrain::warnings() const { return impl_->warnings; }

// The extent as the user shaped it, once: the saved heights or a fresh build (freeze and pastes through
// coherent re-synthesis, s5.3), then the layer stack; and the reference synthesis under it.
Result<const project::ExtentEdit*> Terrain::Impl::extentEdit() {
    std::lock_guard<std::mutex> lock(edit_mutex);
    if (edit_ready) return edit.get();
    auto synthesizer = pool->forThisThread();
    if (!synthesizer) return synthesizer.status();
    const PixelWindow e{project.origin_x, project.origin_y, project.width, project.height};
    auto reference = synthesizer.value()->synthesize(e, world->reference(), 0, false);
    if (!reference) return reference.status();
    Heightfield shaped;
    if (saved_base) {
        shaped = Heightfield(e.width, e.height, pool->database().meters_per_pixel);
        shaped.heights = *saved_base;
    } else if (project::needsIncrementalBuild(world->reference().constraints.get())) {
        auto built = project::buildExtentHeights(*synthesizer.value(), e, world->reference(), project.hold_point_heights,
                                                 project.path);
        if (!built) return built.status();
        shaped = std::move(built.value());
    } else {
        shaped = reference->heights;
    }
    if (project.hasLayers()) {
        auto stack = parseLayerStack(project.layers_json, project.folder());
        if (!stack) return stack.status().withContext(project.path);
        auto layered = applyLayerStack(stack.value(), shaped);
        if (!layered) return layered.status().withContext(project.path);
        if (layered->width != shaped.width || layered->height != shaped.height)
            return Status::error(project.path + ": layer stack changed the terrain size");
        shaped = std::move(layered.value());
    }
    edit = std::make_shared<const project::ExtentEdit>(
        e, std::make_shared<const std::vector<float>>(std::move(shaped.heights)),
        std::make_shared<const std::vector<float>>(std::move(reference->heights.heights)));
    edit_ready = true;
    return edit.get();
}

Result<SynthesisOutput> Terrain::synthesize(const PixelWindow& window, int level, bool want_sources) {
    const project::ExtentEdit* edit = nullptr;
    if (impl_->hasExtentEdit()) {
        auto e = impl_->extentEdit();
        if (!e) return e.status();
        edit = e.value();
    }
    return impl_->world->synthesize(window, level, want_sources, edit);
}

Status Terrain::prepareThisThread() { return impl_->pool->prepareThisThread(); }

Result<Heightfield> Terrain::heights(const PixelWindow& window, int level) {
    auto out = synthesize(window, level, false);
    if (!out) return out.status();
    return std::move(out->heights);
}

Result<std::vector<double>> Terrain::heightsAt(const std::vector<std::array<double, 2>>& points) {
    const project::ExtentEdit* edit = nullptr;
    if (impl_->hasExtentEdit()) {
        auto e = impl_->extentEdit();
        if (!e) return e.status();
        edit = e.value();
    }
    const GridFrame frame{database().meters_per_pixel};
    std::vector<double> out;
    out.reserve(points.size());
    for (const auto& p : points) {
        auto h = impl_->world->heightAt(frame.pixelX(p[0]), frame.pixelY(p[1]), edit);
        if (!h) return h.status();
        out.push_back(h.value());
    }
    return out;
}

Result<double> Terrain::heightAt(double world_x, double world_y) {
    auto h = heightsAt({{world_x, world_y}});
    if (!h) return h.status();
    return h->front();
}

}  // namespace terrasynth
