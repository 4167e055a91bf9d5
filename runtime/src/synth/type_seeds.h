// Private: type seeding (Gain et al. 2015 s5.2) as the correction kernels of both backends read it:
// a pixel whose candidates all miss its target types tries random exemplar pixels of those types.
#pragma once

#include <cstdint>
#include <vector>

#include "terrasynth/database.h"

namespace terrasynth::synth {

// Flattened per-type seed lists of a level: offsets/counts per type (up to kMaxPaintableTypes).
struct SeedTable {
    std::vector<uint32_t> seeds;
    std::vector<int32_t> ranges;  // 2 per type: offset, count
};
SeedTable seedTable(const DatabaseLevel& level);

// Salt of the seeding draws at `level`.
uint32_t seedingSalt(uint32_t seed, int level);

}  // namespace terrasynth::synth
