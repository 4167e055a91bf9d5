// terrasynth/source_usage.h: which parts of the exemplars a synthesis drew from.
//
// A synthesis that copies mostly from the flattest parts of its exemplars looks smooth and
// detail-less even when each pixel is a faithful copy. Given the per-pixel sources of a synthesis
// (SynthesisOutput::source_x/y/exemplar, or a `--sources` map) and the exemplars at the spacing the
// sources refer to, this measures per exemplar
//   * its share of the output pixels, next to its share of the exemplars' pixels (an unbiased
//     synthesis of a multi-exemplar database without type painting keeps the two close), and
//   * the share of its output pixels drawn from its flattest 30% by 9x9 local relief (an unbiased
//     synthesis draws about 30% from there; one that collapses onto valley floors draws ~100%).
//
// Threading: re-entrant; uses only its arguments. Cost: O(exemplar pixels * log) + O(output pixels).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"

namespace terrasynth {

// The flattest `fraction` of a field by local relief (window x window, terrain_stats.h localRelief),
// as a weight per pixel: 1 strictly below the relief quantile, 0 above it, and pixels exactly at the
// quantile (common in DEMs stored in whole metres) share the remainder, so the weights sum to
// fraction * pixels exactly and the exemplar itself scores `fraction`. Preconditions: non-empty
// field, 0 < fraction < 1, odd window >= 3.
std::vector<float> flattestShareWeights(const Heightfield& field, double fraction = 0.3, int window = 9);

struct ExemplarUsage {
    size_t output_pixels = 0;       // output pixels drawn from this exemplar
    double output_share = 0.0;      // output_pixels / all output pixels
    double exemplar_share = 0.0;    // this exemplar's pixels / all exemplars' pixels
    // Share of this exemplar's output pixels drawn from its flattest 30% (flattestShareWeights);
    // NaN when no output pixel comes from it.
    double flattest_share = 0.0;
};

// Per exemplar (same order as `exemplars`, the database order). source_x/y are exemplar pixel
// coordinates at the exemplars' spacing (rounded to the nearest pixel and clamped inside), and
// source_exemplar the exemplar index, per output pixel (equal lengths). Errors: mismatched lengths,
// no output pixels, an empty exemplar, or an exemplar index beyond `exemplars` (named in the message).
Result<std::vector<ExemplarUsage>> measureSourceUsage(const std::vector<Heightfield>& exemplars,
                                                      const std::vector<float>& source_x,
                                                      const std::vector<float>& source_y,
                                                      const std::vector<uint8_t>& source_exemplar,
                                                      double flat_fraction = 0.3, int relief_window = 9);

}  // namespace terrasynth
