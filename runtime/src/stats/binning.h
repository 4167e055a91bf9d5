// Fixed bins of each metric's histogram and the summary of a sample set (docs/realism.md, "Bins").
#pragma once

#include <vector>

#include "terrasynth/terrain_stats.h"

namespace terrasynth::stats {

enum class BinKind {
    SlopeDeg,       // 0..90 deg, 360 linear bins of 0.25 deg
    Curvature,      // +-1 1/m, 400 bins uniform in asinh(k / 1e-4)
    ReliefM,        // 0..5000 m, 300 bins uniform in asinh(relief / 1 m)
    DrainageAreaM2, // 1 m^2 .. 1e13 m^2, 20 log10 bins per decade; distances in decades
};

// Bins with all-zero mass (edges, positions and the log flag filled in).
Histogram emptyHistogram(BinKind kind);

// Histogram plus exact mean, standard deviation, extremes and percentiles of `samples`
// (which it reorders). Non-finite samples must have been left out by the caller.
Distribution describe(std::vector<double>& samples, BinKind kind);

}  // namespace terrasynth::stats
