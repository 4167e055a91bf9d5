// Precondition shared by the per-pixel maps.
#pragma once

#include "terrasynth/heightfield.h"

namespace terrasynth::stats {

inline void requireField(const Heightfield& field) {
    TERRASYNTH_REQUIRE(!field.empty() && field.heights.size() == static_cast<size_t>(field.width) * field.height,
                       "stats need a non-empty heightfield whose sample count matches its size");
}

}  // namespace terrasynth::stats
