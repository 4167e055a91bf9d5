// Placeholder replaced by the curve rasteriser (in progress): no curve contributes yet.
#include "synth/curve_field.h"

namespace terrasynth::synth {

void accumulateCurves(const std::vector<CurveConstraint>&, int, const LevelRegion&, double, std::vector<float>&) {}

}  // namespace terrasynth::synth
