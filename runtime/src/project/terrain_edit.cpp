// Coherent re-synthesis of a project as an edit of another (Gain et al. 2015 s5.3), for the CLI and
// scripts: an edit session opened on the previous version, given the new constraints (and layers)
// as one edit.
#include "terrasynth/edit_session.h"
#include "terrasynth/terrain.h"

namespace terrasynth {
namespace {

Status sameSettings(const Project& a, const Project& b, const ExemplarDatabase& da, const ExemplarDatabase& db) {
    if (da.input_digest != db.input_digest) return Status::error("the projects use different databases");
    if (a.width != b.width || a.height != b.height || a.origin_x != b.origin_x || a.origin_y != b.origin_y)
        return Status::error("the projects cover different extents (size, origin)");
    const SynthesisParams &p = a.synthesis, &q = b.synthesis;
    if (p.seed != q.seed || p.jitter != q.jitter || p.correction_passes != q.correction_passes ||
        p.coarsest_level != q.coarsest_level || p.first_constrained_level != q.first_constrained_level ||
        p.drainage != q.drainage || a.hold_point_heights != b.hold_point_heights)
        return Status::error("the projects' synthesis settings differ (seed, jitter, passes, levels, drainage, "
                             "hold_point_heights)");
    return Status::ok();
}

}  // namespace

Result<Heightfield> Terrain::heightsAfterEditOf(Terrain& previous, PixelWindow* changed, Heightfield* before_heights) {
    const Project& next = project();
    const std::string context = next.path + " as an edit of " + previous.project().path;
    if (Status s = sameSettings(previous.project(), next, previous.database(), database()); !s) return s.withContext(context);
    EditSessionOptions options;
    options.preloaded_database = previous.databasePtr();
    auto session = EditSession::fromProject(previous.project(), options);
    if (!session) return session.status();
    if (before_heights) *before_heights = session.value()->heights();
    const auto& constraints = next.synthesis.constraints;
    auto edited = session.value()->setConstraints(constraints ? *constraints : SynthesisConstraints());
    if (!edited) return edited.status().withContext(context);
    PixelWindow moved = edited.value();
    auto stack = parseLayerStack(next.layers_json, next.folder());
    if (!stack) return stack.status().withContext(next.path);
    if (layerStackToJson(*stack) != layerStackToJson(session.value()->layers())) {
        auto layered = session.value()->setLayers(std::move(stack.value()));
        if (!layered) return layered.status().withContext(context);
        moved = uniteWindows(moved, layered.value());
    }
    if (changed) *changed = moved;
    return session.value()->heights();
}

}  // namespace terrasynth
