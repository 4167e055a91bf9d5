// terrasynth/heightfield.h: the plain heightfield that flows between every stage.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "terrasynth/status.h"

namespace terrasynth {

// A regular grid of heights in metres. Row 0 is north, x grows east, y grows south.
// Ownership: a value type; copying copies the samples. Not synchronised: share read-only.
struct Heightfield {
    int width = 0;
    int height = 0;
    // Ground spacing in metres between neighbouring samples along x (east) and y (south).
    double meters_per_pixel_x = 1.0;
    double meters_per_pixel_y = 1.0;
    // width*height heights in metres, row-major.
    std::vector<float> heights;

    Heightfield() = default;
    Heightfield(int w, int h, double mpp, float fill = 0.0f)
        : width(w), height(h), meters_per_pixel_x(mpp), meters_per_pixel_y(mpp),
          heights(static_cast<size_t>(w) * static_cast<size_t>(h), fill) {}

    bool empty() const { return width <= 0 || height <= 0; }
    size_t size() const { return heights.size(); }
    float& at(int x, int y) { return heights[static_cast<size_t>(y) * width + x]; }
    float at(int x, int y) const { return heights[static_cast<size_t>(y) * width + x]; }
    // Clamp-to-edge access for filters.
    float clamped(int x, int y) const {
        x = x < 0 ? 0 : (x >= width ? width - 1 : x);
        y = y < 0 ? 0 : (y >= height ? height - 1 : y);
        return at(x, y);
    }
};

// Smallest and largest height; {0,0} for an empty field.
struct HeightRange {
    float min = 0.0f;
    float max = 0.0f;
};
HeightRange heightRange(const Heightfield& field);

// Checks that every sample is finite and that the size and spacing are sane
// (1..65536 per side, 0 < spacing <= 100 km). The message names what is wrong.
Status validateHeightfield(const Heightfield& field);

// Resamples to the given spacing (metres per pixel, same on both axes). Heights stay in metres, so
// slopes are preserved. Downsampling low-pass filters first (Gaussian matched to the ratio) so no
// aliasing adds false roughness; upsampling is bicubic. Returns the input when spacing already matches
// within 0.1%.
Heightfield resampleToSpacing(const Heightfield& field, double meters_per_pixel);

}  // namespace terrasynth
