#include "synth/type_seeds.h"

#include "core/hash.h"
#include "terrasynth/constraints.h"

namespace terrasynth::synth {

SeedTable seedTable(const DatabaseLevel& level) {
    SeedTable table;
    table.ranges.assign(2 * kMaxPaintableTypes, 0);
    for (size_t t = 0; t < level.type_seeds.size() && t < static_cast<size_t>(kMaxPaintableTypes); ++t) {
        table.ranges[2 * t] = static_cast<int32_t>(table.seeds.size());
        table.ranges[2 * t + 1] = static_cast<int32_t>(level.type_seeds[t].size());
        table.seeds.insert(table.seeds.end(), level.type_seeds[t].begin(), level.type_seeds[t].end());
    }
    if (table.seeds.empty()) table.seeds.push_back(0);
    return table;
}

uint32_t seedingSalt(uint32_t seed, int level) { return core::levelSalt(seed, level, 3); }

}  // namespace terrasynth::synth
