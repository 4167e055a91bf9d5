// EditSession: saving (the .tsyn, its masks and the edited-heights sidecar, as one FileTransaction)
// and opening from a sidecar.
#include <algorithm>

#include <nlohmann/json.hpp>

#include "core/paths.h"
#include "project/constraints_json.h"
#include "project/edit_session_impl.h"
#include "project/edit_sidecar.h"
#include "project/extent_build.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {

std::string maskStem(const std::string& project_path) {
    return project_path.empty() ? std::string("terrain") : detail::replaceExtension(project_path, "");
}

namespace {

// The canonical form of written constraints, as a project reading them back would give them.
Result<ConstraintsJson> canonical(const ConstraintsJson& written, const ExemplarDatabase& db, const PixelWindow& e) {
    auto parsed = project::parseConstraintsJson(nlohmann::json::parse(written.json), project::masksFrom(written), db, e.x, e.y,
                                              e.width, e.height);
    if (!parsed) return parsed.status();
    return constraintsToJson(*parsed, db, e.x, e.y, e.width, e.height, "canonical");
}

}  // namespace

Status EditSession::save(const std::string& path) {
    Impl& s = *impl_;
    if (s.gesture_depth > 0) return Status::error(path + ": cannot save in the middle of a gesture");
    if (!detail::hasExtension(path, ".tsyn")) return Status::error(path + ": a project file ends in .tsyn");
    const std::string stem = maskStem(path);
    const std::string sidecar_path = stem + ".heights";
    // The project as it will be read back: constraints and layers as JSON (painting as masks
    // beside it), the sidecar named, and the database cache kept where it is.
    const SynthesisConstraints current = s.fullConstraints();
    auto written = constraintsToJson(current, *s.db, s.extent.x, s.extent.y, s.extent.width, s.extent.height, stem);
    if (!written) return written.status().withContext(path);
    Project project = s.project;
    project.constraints_json = written->json;
    project.layers_json = layerStackToJson(s.layers->stack());
    project.synthesis.seed = s.seed;
    project.edited_heights = sidecar_path;
    // A prebuilt database has the levels it has: the project written says so rather than keep a
    // default (database_levels is L, levels 0..L; the format's smallest L is 1).
    if (project.exemplars.empty()) project.database_levels = std::clamp(s.db->levelCount() - 1, 1, 12);
    if (!project.exemplars.empty() && project.database.empty())
        project.database = detail::absolutePath(s.project.databaseCachePath());
    auto canonical_constraints = canonical(*written, *s.db, s.extent);
    if (!canonical_constraints) return canonical_constraints.status().withContext(path);
    auto stack = parseLayerStack(project.layers_json, project.folder());
    if (!stack) return stack.status().withContext(path);

    project::EditSidecar sidecar;
    sidecar.digest = project::editDigest(project, *s.db, *canonical_constraints, layerStackToJson(*stack));
    sidecar.extent = s.extent;
    sidecar.heights = s.terrain->heights().heights;
    sidecar.frozen = s.terrain->frozenMask();
    sidecar.history = s.terrain->history();
    sidecar.lifts = project::liftsOf(&current);
    const SynthesisConstraints* reference = s.world->reference().constraints.get();
    auto reference_json = constraintsToJson(reference ? *reference : SynthesisConstraints(), *s.db, s.extent.x, s.extent.y,
                                            s.extent.width, s.extent.height, "reference");
    if (!reference_json) return reference_json.status().withContext(path);
    sidecar.reference = std::move(reference_json.value());
    sidecar.reference_lifts = project::liftsOf(reference);

    FileTransaction files;
    for (const ConstraintsJson::Mask& mask : written->masks) {
        auto png = encodePng8(mask.width, mask.height, 1, mask.pixels);
        if (!png) return png.status().withContext(mask.file);
        if (Status st = files.stage(mask.file, *png); !st) return st;
    }
    if (Status st = files.stage(sidecar_path, project::encodeEditSidecar(sidecar)); !st) return st;
    if (Status st = files.stage(path, projectToJson(project, detail::folderOf(path))); !st) return st;
    if (Status st = files.commit(); !st) return st;
    // The session now belongs to the file it wrote.
    const uint64_t now = s.edit_count.load();
    s.project = std::move(project);
    s.project.path = path;
    s.project.database = detail::absolutePath(s.project.database);
    s.view_at = ~uint64_t{0};
    s.saved_at = now;
    return Status::ok();
}

Status EditSession::saveIfDirty(const std::string& path, bool* saved) {
    if (saved) *saved = false;
    if (!isDirty() && impl_->project.path == path) return Status::ok();
    Status s = save(path);
    if (s && saved) *saved = true;
    return s;
}

Result<bool> EditSession::Impl::adoptSidecar() {
    const std::string& path = project.edited_heights;
    auto reject = [&](const std::string& why) -> Result<bool> {
        warn(project.path + ": edited heights " + path + " " + why + "; synthesizing the project afresh");
        return false;
    };
    auto bytes = readFileBytes(path);
    if (!bytes) return reject("cannot be read (" + bytes.message() + ")");
    auto digest = project::projectEditDigest(project, *db);
    if (!digest) return digest.status().withContext(project.path);
    auto stored = project::sidecarDigest(*bytes, path);
    if (!stored) return reject("are unusable (" + stored.message() + ")");
    if (*stored != *digest) return reject("belong to another version of the project (digest mismatch)");
    auto sidecar = project::decodeEditSidecar(*bytes, path, /*with_history=*/true);
    if (!sidecar) return reject("are unusable (" + sidecar.message() + ")");
    if (sidecar->extent != extent) return reject("cover another extent");
    auto reference = project::parseConstraintsJson(nlohmann::json::parse(sidecar->reference.json),
                                                 project::masksFrom(sidecar->reference), *db, extent.x, extent.y,
                                                 extent.width, extent.height);
    if (!reference) return reject("hold an unreadable reference (" + reference.message() + ")");
    EditLists lifted = lists;
    if (!project::applyLifts(sidecar->lifts, lifted.points, lifted.curves) ||
        !project::applyLifts(sidecar->reference_lifts, reference->points, reference->curves))
        return reject("hold lifts for other points or curves");
    lists = std::move(lifted);
    SynthesisParams params = project::synthesisOf(project);
    params.constraints = shaping();
    Heightfield heights(extent.width, extent.height, db->meters_per_pixel);
    heights.heights = std::move(sidecar->heights);
    auto restored = IncrementalTerrain::restore(*synthesizer, extent, params, std::move(heights), std::move(sidecar->frozen),
                                                std::move(sidecar->history));
    if (!restored) return reject("do not fit the project (" + restored.message() + ")");
    restored->holdPointHeights(project.hold_point_heights);
    SynthesisParams reference_params = project::synthesisOf(project);
    reference_params.constraints.reset();
    if (!reference->empty()) reference_params.constraints = std::make_shared<const SynthesisConstraints>(std::move(reference.value()));
    auto plain = synthesizer->synthesize(extent, reference_params, 0, false);
    if (!plain) return plain.status();
    terrain = std::move(restored.value());
    reference0 = std::make_shared<const std::vector<float>>(std::move(plain->heights.heights));
    world = std::make_shared<const project::WorldView>(pool, reference_params);
    return true;
}

}  // namespace terrasynth
