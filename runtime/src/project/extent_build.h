// Private: how a project's extent is made from scratch (Terrain, EditSession, the CLI), in one place
// so a session opened without its sidecar gives exactly what Terrain gives.
#pragma once

#include <memory>

#include "terrasynth/incremental.h"
#include "terrasynth/project.h"

namespace terrasynth::project {

// The project's constraints parsed against the database; null when there are none. Errors name
// the project file and the field.
Result<std::shared_ptr<const SynthesisConstraints>> projectConstraints(const Project& project, const ExemplarDatabase& db);

// The project's synthesis settings as every synthesis of it uses them: the free finest levels hold
// the constraints' own pixels when the project holds their heights (hold_point_heights).
SynthesisParams synthesisOf(const Project& project);

// The project's synthesis settings with `constraints`, points and curves lifted once (s5.1,
// hold_point_heights) so every window of the world synthesizes with the same targets: the reference synthesis.
Result<SynthesisParams> referenceParams(Synthesizer& synthesizer, const Project& project,
                                        std::shared_ptr<const SynthesisConstraints> constraints);

// What the correction kernel reads of `c`: points, curves and painting (freeze and pastes are
// driven through coherent re-synthesis instead). Null when that is nothing.
std::shared_ptr<const SynthesisConstraints> shapingOf(const SynthesisConstraints& c);

// Whether the extent needs more than one synthesis: a freeze brush or pastes.
bool needsIncrementalBuild(const SynthesisConstraints* c);

// The extent as a fresh synthesis shapes it (s5.3): without freeze or pastes, the reference
// synthesis; otherwise frozen pixels keep the terrain of the seed alone, the constraints shape the
// rest coherently, then the pastes apply in order. `context` prefixes errors (the project file).
Result<IncrementalTerrain> buildIncrementalExtent(Synthesizer& synthesizer, const PixelWindow& extent,
                                                  const SynthesisParams& reference, bool hold_point_heights,
                                                  const std::string& context);
// The same heights without keeping a history when none is needed.
Result<Heightfield> buildExtentHeights(Synthesizer& synthesizer, const PixelWindow& extent,
                                       const SynthesisParams& reference, bool hold_point_heights,
                                       const std::string& context);

}  // namespace terrasynth::project
