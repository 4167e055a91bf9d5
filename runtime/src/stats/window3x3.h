// The 3x3 neighbourhood of a pixel and its finite-difference derivatives (Zevenbergen & Thorne 1987),
// shared by the slope, curvature and landform maps.
#pragma once

#include "terrasynth/heightfield.h"

namespace terrasynth::stats {

// First and second partial derivatives of height (x east, y south), in m/m and 1/m.
struct Derivatives {
    double zx, zy, zxx, zyy, zxy;
};

// Central differences over the 3x3 window at (x, y), clamped at the border, with the field's own
// x and y spacing.
inline Derivatives derivativesAt(const Heightfield& f, int x, int y) {
    const bool interior = x > 0 && y > 0 && x + 1 < f.width && y + 1 < f.height;
    auto z = [&](int dx, int dy) {
        return static_cast<double>(interior ? f.at(x + dx, y + dy) : f.clamped(x + dx, y + dy));
    };
    const double lx = f.meters_per_pixel_x, ly = f.meters_per_pixel_y;
    const double c = z(0, 0), w = z(-1, 0), e = z(1, 0), n = z(0, -1), s = z(0, 1);
    Derivatives d;
    d.zx = (e - w) / (2.0 * lx);
    d.zy = (s - n) / (2.0 * ly);
    d.zxx = (e - 2.0 * c + w) / (lx * lx);
    d.zyy = (s - 2.0 * c + n) / (ly * ly);
    d.zxy = (z(1, 1) - z(1, -1) - z(-1, 1) + z(-1, -1)) / (4.0 * lx * ly);
    return d;
}

// Below this gradient (rise/run) the downslope direction, hence profile/plan curvature, is undefined.
constexpr double kMinGradientForDirection = 1e-4;

// Second derivatives along the gradient (profile) and along the contour (plan), negated so that
// convex is positive. Only valid when the gradient is at least kMinGradientForDirection.
inline void convexities(const Derivatives& d, double* profile, double* plan) {
    const double p = d.zx * d.zx + d.zy * d.zy;
    const double along = (d.zxx * d.zx * d.zx + 2.0 * d.zxy * d.zx * d.zy + d.zyy * d.zy * d.zy) / p;
    const double across = (d.zxx * d.zy * d.zy - 2.0 * d.zxy * d.zx * d.zy + d.zyy * d.zx * d.zx) / p;
    *profile = -along;
    *plan = -across;
}

}  // namespace terrasynth::stats
