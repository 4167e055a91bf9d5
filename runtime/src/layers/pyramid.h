// Laplacian / Gaussian pyramids (Burt & Adelson 1983), the representation in which every layer is
// stored and blended (Bradbury et al. 2014, s3.2).
//
// Laplacian pyramids use the 11-tap half-band kernel (3, 0, -25, 0, 150, 256, 150, 0, -25, 0, 3)/512,
// whose expand() is 6-point Lagrange interpolation: its passband is flat to 1e-4 an octave below the
// cut and its stopband a few percent half an octave above it, so a band holds mostly its own octaves (the 5-tap binomial kernel of Burt & Adelson leaks ~7% of the amplitude two octaves away,
// which on red-spectrum terrain is most of a "high" band). Mask pyramids use the binomial kernel,
// which never overshoots [0, 1]. Level i+1 has ceil(size_i / 2) samples per side; borders clamp. A Laplacian pyramid of depth D
// holds D detail levels L_0..L_{D-1} (L_i = G_i - expand(G_{i+1})) and the Gaussian residual G_D,
// so collapsing with the same expand() reproduces the input up to float rounding.
#pragma once

#include <cstddef>
#include <vector>

#include "terrasynth/heightfield.h"

namespace terrasynth::layers {

struct Plane {
    int width = 0;
    int height = 0;
    std::vector<float> samples;

    Plane() = default;
    Plane(int w, int h, float fill = 0.0f) : width(w), height(h), samples(static_cast<size_t>(w) * h, fill) {}
    float* row(int y) { return samples.data() + static_cast<size_t>(y) * width; }
    const float* row(int y) const { return samples.data() + static_cast<size_t>(y) * width; }
};

// Inclusive-exclusive rectangle of samples; empty when x0 >= x1 or y0 >= y1.
struct Box {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
};

struct Pyramid {
    std::vector<Plane> levels;  // depth detail levels, then the residual
    int depth() const { return static_cast<int>(levels.size()) - 1; }
};

inline int coarserSize(int n) { return (n + 1) / 2; }

enum class Kernel { HalfBand, Binomial };

// out = blur-and-decimate(in).
void reduce(const Plane& in, Plane& out, Kernel kernel = Kernel::HalfBand);
// out = expand(coarse) sized fine_w x fine_h, plus `add` when given (same size as out).
void expand(const Plane& coarse, int fine_w, int fine_h, Plane& out, const Plane* add = nullptr);
// Expands rows [y0, y1) of the fine level into `out_rows` (row-major, fine_w wide), adding to what is
// there when `accumulate`. The building block for fused recomposition.
void expandRows(const Plane& coarse, int fine_w, int fine_h, int y0, int y1, float* out_rows, bool accumulate);

Pyramid buildLaplacian(const Plane& image, int depth);
Pyramid buildGaussian(const Plane& image, int depth, Kernel kernel = Kernel::Binomial);
Plane collapse(const Pyramid& laplacian);

inline Plane toPlane(const Heightfield& f) {
    Plane p;
    p.width = f.width;
    p.height = f.height;
    p.samples = f.heights;
    return p;
}
inline Heightfield toField(Plane p, const Heightfield& like) {
    Heightfield f;
    f.width = p.width;
    f.height = p.height;
    f.meters_per_pixel_x = like.meters_per_pixel_x;
    f.meters_per_pixel_y = like.meters_per_pixel_y;
    f.heights = std::move(p.samples);
    return f;
}

// Bounding box of the samples that are not exactly zero (empty box when all are zero).
Box nonZeroBox(const Plane& plane);

}  // namespace terrasynth::layers
