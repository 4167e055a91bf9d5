// Private: where synthesis starts (issue 16). The coarsest synthesized level is the coarsest one at
// which most of the database is still large enough to synthesize from, and it starts from
// irregular patches of exemplar coordinates rather than from independent random coordinates.
//
// Why: on an exemplar of a few pixels (648 px at level 6 is 10x10), and from per-pixel random
// coordinates, every neighbourhood is inconsistent, and eq. 7 (a squared distance to the average of
// the neighbourhood) is smallest for the flattest candidates. Flat coordinates only have flat
// k-coherence candidates (eq. 3), so the choice is never undone at the finer levels: one-exemplar
// syntheses of mixed exemplars drew 100% of their pixels from the flattest 30% of the exemplar.
// Started from coherent patches on a level where the exemplar is at least kMinCoarsestSide
// pixels, the finer levels keep the exemplar's mix (docs/realism.md has the figures).
#pragma once

#include <cstdint>
#include <vector>

#include "terrasynth/database.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::synth {

// Correction passes added at the coarsest synthesized level. Starting from a level where the
// exemplars are large, the first level holds whole exemplar slopes; point and curve constraints
// pull halfway per pass (eq. 8-9) and now act on fewer levels than when synthesis started at the
// database's coarsest level, so the broad slope they ask for needs more pulls there. The level
// holds about 1/256 of the output's pixels: the cost is negligible.
constexpr int kCoarsestLevelExtraPasses = 2;

// The coarsest level at which exemplars holding at least half of the database's level-0 pixels are
// still kMinCoarsestSide pixels on their shorter side (0 when none is).
int automaticCoarsestLevel(const ExemplarDatabase& db);

// Per exemplar of a level, the running total of interior pixels (those at least kInteriorMargin
// from its edges), scaled by a common power of two so the total stays below 2^31: patches pick
// exemplars in proportion to their area. The last entry is the total (> 0 for a built database).
std::vector<uint32_t> cumulativeInteriorAreas(const DatabaseLevel& level);

}  // namespace terrasynth::synth
