#include "terrasynth_host/frame_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace terrasynth::host {

SeriesSummary summarize(std::vector<double> values) {
    SeriesSummary s;
    s.count = values.size();
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    s.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
    const size_t n = values.size();
    s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    // Nearest rank: the smallest value with at least 95% of the values at or below it.
    const size_t rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(n)));
    s.p95 = values[std::max<size_t>(rank, 1) - 1];
    s.max = values.back();
    return s;
}

std::vector<double> FrameTimeSeries::column(double FrameTiming::*member) const {
    std::vector<double> out;
    out.reserve(frames_.size());
    for (const FrameTiming& f : frames_) out.push_back(f.*member);
    return out;
}

std::vector<double> FrameTimeSeries::mainThread() const {
    std::vector<double> out;
    out.reserve(frames_.size());
    for (const FrameTiming& f : frames_) out.push_back(f.mainThreadMs());
    return out;
}

std::vector<double> FrameTimeSeries::gl() const {
    std::vector<double> out;
    out.reserve(frames_.size());
    for (const FrameTiming& f : frames_) out.push_back(f.glMs());
    return out;
}

}  // namespace terrasynth::host
