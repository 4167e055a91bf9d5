// Source usage of a synthesis (terrasynth/source_usage.h): per exemplar, its share of the output and
// the share drawn from its flattest 30% by local relief.
#include "terrasynth/source_usage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "stats/field_check.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {

std::vector<float> flattestShareWeights(const Heightfield& field, double fraction, int window) {
    stats::requireField(field);
    TERRASYNTH_REQUIRE(fraction > 0.0 && fraction < 1.0, "flat fraction must be in (0, 1)");
    const std::vector<float> relief = localRelief(field, window);
    std::vector<float> sorted(relief);
    const size_t wanted = static_cast<size_t>(std::llround(fraction * static_cast<double>(relief.size())));
    if (wanted == 0) return std::vector<float>(relief.size(), 0.0f);
    std::nth_element(sorted.begin(), sorted.begin() + (wanted - 1), sorted.end());
    const float quantile = sorted[wanted - 1];
    size_t below = 0, at = 0;
    for (float r : relief) below += r < quantile, at += r == quantile;
    // Pixels at the quantile share what the strictly flatter ones leave of `wanted`.
    const float tie_weight = at ? static_cast<float>(static_cast<double>(wanted - below) / static_cast<double>(at)) : 0.0f;
    std::vector<float> weights(relief.size());
    for (size_t i = 0; i < relief.size(); ++i)
        weights[i] = relief[i] < quantile ? 1.0f : (relief[i] == quantile ? tie_weight : 0.0f);
    return weights;
}

Result<std::vector<ExemplarUsage>> measureSourceUsage(const std::vector<Heightfield>& exemplars,
                                                      const std::vector<float>& source_x,
                                                      const std::vector<float>& source_y,
                                                      const std::vector<uint8_t>& source_exemplar,
                                                      double flat_fraction, int relief_window) {
    const size_t n = source_exemplar.size();
    if (source_x.size() != n || source_y.size() != n)
        return Status::error("source maps of different lengths (" + std::to_string(source_x.size()) + ", " +
                             std::to_string(source_y.size()) + ", " + std::to_string(n) + ")");
    if (n == 0) return Status::error("no output pixels");
    if (exemplars.empty()) return Status::error("no exemplars");
    std::vector<std::vector<float>> flat(exemplars.size());
    size_t all_pixels = 0;
    for (size_t e = 0; e < exemplars.size(); ++e) {
        if (exemplars[e].empty() || exemplars[e].heights.size() != exemplars[e].size())
            return Status::error("exemplar " + std::to_string(e) + " is empty");
        flat[e] = flattestShareWeights(exemplars[e], flat_fraction, relief_window);
        all_pixels += exemplars[e].size();
    }
    std::vector<ExemplarUsage> usage(exemplars.size());
    std::vector<double> flat_sum(exemplars.size(), 0.0);
    for (size_t i = 0; i < n; ++i) {
        const size_t e = source_exemplar[i];
        if (e >= exemplars.size())
            return Status::error("output pixel " + std::to_string(i) + " names exemplar " + std::to_string(e) +
                                 ", but there are only " + std::to_string(exemplars.size()));
        const Heightfield& f = exemplars[e];
        const int x = std::clamp(static_cast<int>(std::lround(source_x[i])), 0, f.width - 1);
        const int y = std::clamp(static_cast<int>(std::lround(source_y[i])), 0, f.height - 1);
        ++usage[e].output_pixels;
        flat_sum[e] += flat[e][static_cast<size_t>(y) * f.width + x];
    }
    for (size_t e = 0; e < exemplars.size(); ++e) {
        usage[e].output_share = static_cast<double>(usage[e].output_pixels) / static_cast<double>(n);
        usage[e].exemplar_share = static_cast<double>(exemplars[e].size()) / static_cast<double>(all_pixels);
        usage[e].flattest_share = usage[e].output_pixels ? flat_sum[e] / static_cast<double>(usage[e].output_pixels)
                                                         : std::numeric_limits<double>::quiet_NaN();
    }
    return usage;
}

}  // namespace terrasynth
