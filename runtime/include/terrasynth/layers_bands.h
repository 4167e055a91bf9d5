// terrasynth/layers_bands.h: the three frequency bands every layer is split into
// (Bradbury et al. 2014, s3.2).
//
// A heightfield is decomposed into a Laplacian pyramid (Burt & Adelson 1983, 5-tap binomial kernel,
// clamped borders). Pyramid level i holds wavelengths of roughly 2^(i+1)..2^(i+2) pixels; the levels
// are grouped into three bands by two cut wavelengths:
//   high: wavelengths below `high_mid_cut_px`            (levels 0 .. log2(high_mid_cut_px)-2)
//   mid : from `high_mid_cut_px` to `mid_low_cut_px`      (the following levels)
//   low : above `mid_low_cut_px`                           (the Gaussian residual, 1/(mid_low_cut_px/2) size)
// Defaults (8 px and 64 px) put single ridgelets in mid and mountain-scale relief in low.
// The paper uses exactly three bands because more gives the artist no extra control (s3.2).
//
// Threading: all functions are re-entrant; large images are processed on all cores.
#pragma once

#include "terrasynth/heightfield.h"
#include "terrasynth/status.h"

namespace terrasynth {

enum class Band : int { Low = 0, Mid = 1, High = 2 };

// Blend strength of each band of one layer ("alpha" of the paper's sub-layer sliders).
// 0 removes the band's contribution, 1 is neutral, values above 1 exaggerate it. Range [0, 4].
struct BandWeights {
    float low = 1.0f;
    float mid = 1.0f;
    float high = 1.0f;

    float get(Band b) const { return b == Band::Low ? low : (b == Band::Mid ? mid : high); }
    bool operator==(const BandWeights& o) const { return low == o.low && mid == o.mid && high == o.high; }
    bool operator!=(const BandWeights& o) const { return !(*this == o); }
};
constexpr float kMaxBandWeight = 4.0f;

// The two cut wavelengths, in pixels of the terrain grid. Both powers of two,
// 4 <= high_mid_cut_px < mid_low_cut_px <= 1024.
struct BandSplit {
    int high_mid_cut_px = 8;
    int mid_low_cut_px = 64;

    int highLevels() const;  // pyramid levels in the high band
    int depth() const;       // detail levels in the pyramid; the residual is level depth()
    Band bandOfLevel(int level) const;
    bool operator==(const BandSplit& o) const {
        return high_mid_cut_px == o.high_mid_cut_px && mid_low_cut_px == o.mid_low_cut_px;
    }
};
// Message names the offending cut, e.g. "mid_low_cut_px: must be a power of two, got 60".
Status validateBandSplit(const BandSplit& split);

// The three bands at full resolution (for display as sub-layers and for analysis).
// low + mid + high equals the input up to float rounding.
struct BandDecomposition {
    Heightfield low, mid, high;
};
BandDecomposition decomposeBands(const Heightfield& field, const BandSplit& split = {});

// Decomposes and recomposes with per-band weights; unit weights reproduce the input to within
// float rounding (about 1e-7 of the relief).
Heightfield reweightBands(const Heightfield& field, const BandWeights& weights, const BandSplit& split = {});

}  // namespace terrasynth
