// Coherent re-synthesis of a project as an edit of another (Gain et al. 2015 s5.3), for the CLI and
// scripts: the editor's IncrementalTerrain, driven by the difference between two projects.
#include <cmath>

#include "terrasynth/incremental.h"
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
    auto unsupported = [](const Project& p) {
        const auto& c = p.synthesis.constraints;
        return !p.layers.empty() || (c && !c->pastes.empty());
    };
    if (unsupported(a) || unsupported(b)) return Status::error("pastes and layers are not supported in a coherent edit");
    return Status::ok();
}

}  // namespace

Result<Heightfield> Terrain::heightsAfterEditOf(Terrain& previous, PixelWindow* changed, Heightfield* before_heights) {
    Status s = sameSettings(previous.project_, project_, *previous.db_, *db_);
    if (!s) return s.withContext(project_.path + " as an edit of " + previous.project_.path);
    auto synthesizer = synthesizerForThisThread();
    if (!synthesizer) return synthesizer.status();
    const auto& before = previous.project_.synthesis.constraints;
    // The previous terrain as Terrain::heights() makes it: with a freeze brush, frozen pixels keep
    // the terrain of the seed alone and the constraints shape the rest coherently.
    const bool frozen_before = before && !before->freeze.empty();
    SynthesisParams start = previous.project_.synthesis;
    if (frozen_before) start.constraints.reset();
    auto incremental = IncrementalTerrain::create(*synthesizer.value(), extent(), start);
    if (!incremental) return incremental.status();
    incremental->holdPointHeights(project_.hold_point_heights);
    if (frozen_before) {
        incremental->freeze(before->freeze);
        if (before->shapesTerrain()) {
            auto shaping = std::make_shared<SynthesisConstraints>(*before);
            shaping->freeze = TypePaint();
            s = incremental->update(shaping, extent());
            if (!s) return s.withContext(previous.project_.path);
        }
    }
    const auto& after = project_.synthesis.constraints;
    if (after && !after->freeze.empty()) incremental->freeze(after->freeze);
    // Points the edit left alone keep the lift they had, so only edited points count as changed.
    auto next = std::make_shared<SynthesisConstraints>(after ? *after : SynthesisConstraints());
    next->freeze = TypePaint();
    if (const auto& current = incremental->params().constraints)
        for (PointConstraint& p : next->points)
            for (const PointConstraint& q : current->points)
                if (p.samePlacement(q)) p.lift_m = q.lift_m;
    if (before_heights) *before_heights = incremental->heights();
    s = incremental->applyEdit(next, changed);
    if (!s) return s.withContext(project_.path);
    return incremental->heights();
}

}  // namespace terrasynth
