#include "layers/pyramid.h"

#include <algorithm>
#include <cmath>

#include "layers/parallel.h"

namespace terrasynth::layers {
namespace {

inline int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

// Horizontal half of expand(): t (coarse_w samples) -> out (fine_w samples). Even outputs are the
// coarse samples, odd ones the 6-point Lagrange midpoint (3, -25, 150, 150, -25, 3)/256.
inline void expandRowH(const float* t, int coarse_w, float* out, int fine_w, bool accumulate) {
    const int last = coarse_w - 1;
    for (int x = 0; x < fine_w; ++x) {
        const int j = x >> 1;
        float v;
        if ((x & 1) == 0) {
            v = t[j];
        } else {
            v = (150.0f * (t[j] + t[clampi(j + 1, 0, last)]) - 25.0f * (t[clampi(j - 1, 0, last)] + t[clampi(j + 2, 0, last)]) +
                 3.0f * (t[clampi(j - 2, 0, last)] + t[clampi(j + 3, 0, last)])) *
                (1.0f / 256.0f);
        }
        out[x] = accumulate ? out[x] + v : v;
    }
}

}  // namespace

void reduce(const Plane& in, Plane& out, Kernel kernel) {
    const int ow = coarserSize(in.width), oh = coarserSize(in.height);
    if (out.width != ow || out.height != oh) out = Plane(ow, oh);
    const int w = in.width, last_y = in.height - 1, last_x = in.width - 1;
    const bool half = kernel == Kernel::HalfBand;
    parallelFor(oh, 5L * w, [&](int y0, int y1) {
        std::vector<float> t(w);
        for (int k = y0; k < y1; ++k) {
            const int c = 2 * k;
            float* o = out.row(k);
            if (half) {
                const float* rm5 = in.row(clampi(c - 5, 0, last_y));
                const float* rm3 = in.row(clampi(c - 3, 0, last_y));
                const float* rm1 = in.row(clampi(c - 1, 0, last_y));
                const float* r0 = in.row(clampi(c, 0, last_y));
                const float* rp1 = in.row(clampi(c + 1, 0, last_y));
                const float* rp3 = in.row(clampi(c + 3, 0, last_y));
                const float* rp5 = in.row(clampi(c + 5, 0, last_y));
                for (int x = 0; x < w; ++x)
                    t[x] = (256.0f * r0[x] + 150.0f * (rm1[x] + rp1[x]) - 25.0f * (rm3[x] + rp3[x]) +
                            3.0f * (rm5[x] + rp5[x])) *
                           (1.0f / 512.0f);
                for (int j = 0; j < ow; ++j) {
                    const int q = 2 * j;
                    o[j] = (256.0f * t[q] + 150.0f * (t[clampi(q - 1, 0, last_x)] + t[clampi(q + 1, 0, last_x)]) -
                            25.0f * (t[clampi(q - 3, 0, last_x)] + t[clampi(q + 3, 0, last_x)]) +
                            3.0f * (t[clampi(q - 5, 0, last_x)] + t[clampi(q + 5, 0, last_x)])) *
                           (1.0f / 512.0f);
                }
            } else {
                const float* r0 = in.row(clampi(c - 2, 0, last_y));
                const float* r1 = in.row(clampi(c - 1, 0, last_y));
                const float* r2 = in.row(clampi(c, 0, last_y));
                const float* r3 = in.row(clampi(c + 1, 0, last_y));
                const float* r4 = in.row(clampi(c + 2, 0, last_y));
                for (int x = 0; x < w; ++x)
                    t[x] = (r0[x] + r4[x] + 4.0f * (r1[x] + r3[x]) + 6.0f * r2[x]) * (1.0f / 16.0f);
                for (int j = 0; j < ow; ++j) {
                    const int q = 2 * j;
                    o[j] = (t[clampi(q - 2, 0, last_x)] + t[clampi(q + 2, 0, last_x)] +
                            4.0f * (t[clampi(q - 1, 0, last_x)] + t[clampi(q + 1, 0, last_x)]) + 6.0f * t[q]) *
                           (1.0f / 16.0f);
                }
            }
        }
    });
}

void expandRows(const Plane& coarse, int fine_w, int fine_h, int y0, int y1, float* out_rows, bool accumulate) {
    const int cw = coarse.width, last = coarse.height - 1;
    std::vector<float> t(cw);
    for (int y = y0; y < y1; ++y) {
        const int k = y >> 1;
        const float* src;
        if ((y & 1) == 0) {
            src = coarse.row(k);
        } else {
            const float* a = coarse.row(clampi(k - 2, 0, last));
            const float* b = coarse.row(clampi(k - 1, 0, last));
            const float* c = coarse.row(k);
            const float* d = coarse.row(clampi(k + 1, 0, last));
            const float* e = coarse.row(clampi(k + 2, 0, last));
            const float* f = coarse.row(clampi(k + 3, 0, last));
            for (int x = 0; x < cw; ++x)
                t[x] = (150.0f * (c[x] + d[x]) - 25.0f * (b[x] + e[x]) + 3.0f * (a[x] + f[x])) * (1.0f / 256.0f);
            src = t.data();
        }
        expandRowH(src, cw, out_rows + static_cast<size_t>(y - y0) * fine_w, fine_w, accumulate);
    }
    (void)fine_h;
}

void expand(const Plane& coarse, int fine_w, int fine_h, Plane& out, const Plane* add) {
    if (out.width != fine_w || out.height != fine_h) out = Plane(fine_w, fine_h);
    parallelFor(fine_h, 4L * fine_w, [&](int y0, int y1) {
        if (add) std::copy(add->row(y0), add->row(y0) + static_cast<size_t>(y1 - y0) * fine_w, out.row(y0));
        expandRows(coarse, fine_w, fine_h, y0, y1, out.row(y0), add != nullptr);
    });
}

Pyramid buildGaussian(const Plane& image, int depth, Kernel kernel) {
    Pyramid p;
    p.levels.resize(depth + 1);
    p.levels[0] = image;
    for (int i = 0; i < depth; ++i) reduce(p.levels[i], p.levels[i + 1], kernel);
    return p;
}

Pyramid buildLaplacian(const Plane& image, int depth) {
    Pyramid p = buildGaussian(image, depth, Kernel::HalfBand);
    Plane up;
    for (int i = 0; i < depth; ++i) {
        Plane& g = p.levels[i];
        expand(p.levels[i + 1], g.width, g.height, up);
        const size_t n = g.samples.size();
        float* gs = g.samples.data();
        const float* us = up.samples.data();
        for (size_t k = 0; k < n; ++k) gs[k] -= us[k];
    }
    return p;
}

Plane collapse(const Pyramid& laplacian) {
    Plane current = laplacian.levels.back();
    for (int i = laplacian.depth() - 1; i >= 0; --i) {
        const Plane& l = laplacian.levels[i];
        Plane next;
        expand(current, l.width, l.height, next, &l);
        current = std::move(next);
    }
    return current;
}

Box nonZeroBox(const Plane& plane) {
    Box b{plane.width, plane.height, 0, 0};
    for (int y = 0; y < plane.height; ++y) {
        const float* r = plane.row(y);
        int first = -1, last = -1;
        for (int x = 0; x < plane.width; ++x)
            if (r[x] != 0.0f) {
                if (first < 0) first = x;
                last = x;
            }
        if (first < 0) continue;
        b.x0 = std::min(b.x0, first);
        b.x1 = std::max(b.x1, last + 1);
        b.y0 = std::min(b.y0, y);
        b.y1 = std::max(b.y1, y + 1);
    }
    if (b.x0 >= b.x1) return Box{};
    return b;
}

}  // namespace terrasynth::layers
