#include "synth/synthesis_plan.h"

namespace terrasynth::synth {

SynthesisPlan planSynthesis(const PixelWindow& window, int output_level, int coarsest_level, int passes,
                            const std::vector<int>& extra_margin) {
    TERRASYNTH_REQUIRE(output_level >= 0 && output_level <= coarsest_level, "output level above the coarsest");
    TERRASYNTH_REQUIRE(window.width > 0 && window.height > 0, "empty window");
    SynthesisPlan plan;
    plan.output_level = output_level;
    plan.coarsest_level = coarsest_level;
    plan.passes = passes;
    plan.regions.resize(coarsest_level + 1);
    plan.needed.resize(coarsest_level + 1);
    plan.output = {static_cast<int>(window.x), static_cast<int>(window.y), window.width, window.height};
    const int correction_margin = kSubpassReach * 4 * passes;
    LevelRegion needed = plan.output;  // what must be valid after correction at this level
    for (int level = output_level; level <= coarsest_level; ++level) {
        plan.needed[level] = needed;
        LevelRegion& r = plan.regions[level];
        const int margin = correction_margin + (level < static_cast<int>(extra_margin.size()) ? extra_margin[level] : 0);
        r = {needed.x - margin, needed.y - margin, needed.width + 2 * margin, needed.height + 2 * margin};
        // Parents of r at the next level.
        const int x0 = floorDiv2(r.x), y0 = floorDiv2(r.y);
        const int x1 = floorDiv2(r.x + r.width - 1), y1 = floorDiv2(r.y + r.height - 1);
        needed = {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
    }
    return plan;
}

}  // namespace terrasynth::synth
