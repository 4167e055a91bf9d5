// Private: coherence (Gain et al. 2015 s5.3) prepared for one level / pass of a synthesis region.
#pragma once

#include <cstdint>
#include <vector>

#include "synth/synthesis_plan.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::synth {

constexpr uint32_t kNoPrevious = 0xffffffffu;

// W^i codes (Coherence values) per region pixel: Frozen if any level-0 pixel below is frozen
// (recursively over 2x2 blocks), else the most frequent code (ties: the freer one).
std::vector<uint8_t> coherenceCodes(const CoherenceMap* map, int level, const LevelRegion& region);

// The previous result of (level, pass) mapped onto `region` by global coordinates; kNoPrevious
// where the history has no pixel. Empty vectors when there is no history for that level and pass.
struct PassHistory {
    std::vector<uint32_t> index;
    std::vector<float> v;
};
PassHistory previousPass(const SynthesisHistory* history, int level, int pass, const LevelRegion& region);

}  // namespace terrasynth::synth
