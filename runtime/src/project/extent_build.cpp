#include "project/extent_build.h"

namespace terrasynth::project {

Result<std::shared_ptr<const SynthesisConstraints>> projectConstraints(const Project& p, const ExemplarDatabase& db) {
    auto parsed = parseConstraints(p.constraints_json, p.folder(), db, p.origin_x, p.origin_y, p.width, p.height);
    if (!parsed) return parsed.status().withContext(p.path);
    if (parsed->empty()) return std::shared_ptr<const SynthesisConstraints>();
    return std::make_shared<const SynthesisConstraints>(std::move(parsed.value()));
}

SynthesisParams synthesisOf(const Project& project) {
    SynthesisParams params = project.synthesis;
    params.hold_on_free_levels = project.hold_point_heights;
    return params;
}

Result<SynthesisParams> referenceParams(Synthesizer& synthesizer, const Project& project,
                                        std::shared_ptr<const SynthesisConstraints> constraints) {
    SynthesisParams params = synthesisOf(project);
    params.constraints = std::move(constraints);
    params.previous.reset();
    params.coherence.reset();
    params.record_history = false;
    if (project.hold_point_heights && params.constraints && !params.constraints->points.empty()) {
        auto lifted = liftPointConstraints(synthesizer, params);
        if (!lifted) return lifted.status().withContext(project.path + ": constraints.points");
        params.constraints = std::move(lifted.value());
    }
    if (project.hold_point_heights && params.constraints && !params.constraints->curves.empty()) {
        auto lifted = liftCurveConstraints(synthesizer, params);
        if (!lifted) return lifted.status().withContext(project.path + ": constraints.curves");
        params.constraints = std::move(lifted.value());
    }
    return params;
}

std::shared_ptr<const SynthesisConstraints> shapingOf(const SynthesisConstraints& c) {
    if (!c.shapesTerrain()) return nullptr;
    auto shaping = std::make_shared<SynthesisConstraints>();
    shaping->points = c.points;
    shaping->curves = c.curves;
    shaping->types = c.types;
    return shaping;
}

bool needsIncrementalBuild(const SynthesisConstraints* c) { return c && (!c->freeze.empty() || !c->pastes.empty()); }

Result<IncrementalTerrain> buildIncrementalExtent(Synthesizer& synthesizer, const PixelWindow& extent,
                                                  const SynthesisParams& reference, bool hold_point_heights,
                                                  const std::string& context) {
    const SynthesisConstraints* c = reference.constraints.get();
    if (!needsIncrementalBuild(c)) {
        SynthesisParams params = reference;
        if (c) params.constraints = shapingOf(*c);
        auto terrain = IncrementalTerrain::create(synthesizer, extent, params);
        if (terrain) terrain->holdPointHeights(hold_point_heights);
        return terrain;
    }
    // Frozen pixels keep the terrain the seed alone makes; constraints act everywhere else.
    SynthesisParams plain = reference;
    plain.constraints.reset();
    auto terrain = IncrementalTerrain::create(synthesizer, extent, plain);
    if (!terrain) return terrain.status();
    terrain->holdPointHeights(hold_point_heights);
    terrain->freeze(c->freeze);
    if (auto shaping = shapingOf(*c)) {
        if (Status s = terrain->update(shaping, extent); !s) return s.withContext(context);
    }
    for (size_t i = 0; i < c->pastes.size(); ++i)
        if (Status s = terrain->paste(c->pastes[i]); !s) return s.withContext(context + ": constraints.pastes[" + std::to_string(i) + "]");
    return terrain;
}

Result<Heightfield> buildExtentHeights(Synthesizer& synthesizer, const PixelWindow& extent, const SynthesisParams& reference,
                                       bool hold_point_heights, const std::string& context) {
    if (!needsIncrementalBuild(reference.constraints.get())) {
        auto out = synthesizer.synthesize(extent, reference, 0, false);
        if (!out) return out.status();
        return std::move(out->heights);
    }
    auto terrain = buildIncrementalExtent(synthesizer, extent, reference, hold_point_heights, context);
    if (!terrain) return terrain.status();
    return terrain->heights();
}

}  // namespace terrasynth::project
