// Peaks of s4.2: a Gaussian of given height and spread, reshaped by skewness and kurtosis.
//
// The cross-section along the skew axis is a two-piece generalised Gaussian exp(-(|u|/s)^beta) with
// s = scale_forward ahead of the summit and scale_backward behind it. Read as a distribution its
// moments have closed forms, so (beta, scale ratio) are solved so that the standard deviation,
// skewness and excess kurtosis are exactly the artist's values.
#include <algorithm>
#include <cmath>
#include <string>

#include "layers/parallel.h"
#include "terrasynth/layers_tools.h"

namespace terrasynth {
namespace {

struct Moments {
    double variance, skewness, kurtosis;
};

// Two-piece generalised Gaussian with backward scale 1 and forward scale r.
Moments twoPieceMoments(double beta, double r) {
    const double g1 = std::lgamma(1.0 / beta);
    double m[5];
    for (int k = 1; k <= 4; ++k) m[k] = std::exp(std::lgamma((k + 1.0) / beta) - g1);
    double raw[5];
    for (int k = 1; k <= 4; ++k)
        raw[k] = (std::pow(r, k + 1) + ((k % 2) ? -1.0 : 1.0)) / (r + 1.0) * m[k];
    const double mu = raw[1];
    const double var = raw[2] - mu * mu;
    const double mu3 = raw[3] - 3 * mu * raw[2] + 2 * mu * mu * mu;
    const double mu4 = raw[4] - 4 * mu * raw[3] + 6 * mu * mu * raw[2] - 3 * mu * mu * mu * mu;
    return {var, mu3 / std::pow(var, 1.5), mu4 / (var * var) - 3.0};
}

// Scale ratio giving |skewness| at this beta (skewness grows monotonically with r); < 0 if out of reach.
double ratioForSkew(double beta, double skew) {
    if (skew <= 0.0) return 1.0;
    double lo = 1.0, hi = 200.0;
    if (twoPieceMoments(beta, hi).skewness < skew) return -1.0;
    for (int it = 0; it < 100; ++it) {
        const double mid = std::sqrt(lo * hi);
        (twoPieceMoments(beta, mid).skewness < skew ? lo : hi) = mid;
    }
    return std::sqrt(lo * hi);
}

double kurtosisAt(double beta, double skew, double* ratio) {
    *ratio = ratioForSkew(beta, skew);
    return *ratio < 0 ? NAN : twoPieceMoments(beta, *ratio).kurtosis;
}

}  // namespace

Result<PeakShape> solvePeakShape(const PeakParams& p) {
    if (!(p.spread_px > 0.0 && p.spread_px <= 1.0e5)) return Status::error("spread_px: must be > 0");
    if (!std::isfinite(p.height_m) || std::fabs(p.height_m) > 1.0e4)
        return Status::error("height_m: must be finite with |height_m| <= 10000");
    if (!(std::fabs(p.skewness) < 0.9)) return Status::error("skewness: must be in (-0.9, 0.9)");
    if (!(p.kurtosis >= -1.1 && p.kurtosis <= 6.0)) return Status::error("kurtosis: must be in [-1.1, 6]");
    if (!std::isfinite(p.center_x) || !std::isfinite(p.center_y)) return Status::error("center: must be finite");
    const double skew = std::fabs(p.skewness);
    // Kurtosis falls as beta grows (needle -> Gaussian -> mesa) until, for skewed peaks, the scale
    // ratio the skewness needs starts to raise it again: solve on the falling branch.
    double r = 1.0, lo = std::log(0.45), hi = lo, k_min = INFINITY;
    const double k_max = kurtosisAt(std::exp(lo), skew, &r);
    for (int i = 0; i <= 64; ++i) {
        const double lb = std::log(0.45) + (std::log(40.0) - std::log(0.45)) * i / 64.0;
        const double k = kurtosisAt(std::exp(lb), skew, &r);
        if (!std::isnan(k) && k < k_min) k_min = k, hi = lb;
    }
    if (std::isnan(k_max) || !std::isfinite(k_min))
        return Status::error("skewness: " + std::to_string(p.skewness) + " is out of reach of the peak family");
    if (p.kurtosis < k_min || p.kurtosis > k_max)
        return Status::error("kurtosis: with skewness " + std::to_string(p.skewness) + " must be in [" +
                             std::to_string(k_min) + ", " + std::to_string(k_max) + "]");
    for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        const double k = kurtosisAt(std::exp(mid), skew, &r);
        (std::isnan(k) || k < p.kurtosis ? hi : lo) = mid;
    }
    PeakShape s;
    s.beta = std::exp(0.5 * (lo + hi));
    kurtosisAt(s.beta, skew, &r);
    const double unit_sd = std::sqrt(twoPieceMoments(s.beta, r).variance);
    const double back = p.spread_px / unit_sd, fwd = r * back;
    s.scale_forward = p.skewness >= 0 ? fwd : back;
    s.scale_backward = p.skewness >= 0 ? back : fwd;
    s.scale_side = p.spread_px * std::exp(0.5 * (std::lgamma(1.0 / s.beta) - std::lgamma(3.0 / s.beta)));
    return s;
}

double peakFootprintRadius(const PeakParams& p, const PeakShape& shape, double fraction) {
    return shape.scale_side * std::pow(std::log(1.0 / fraction), 1.0 / shape.beta);
}

Result<Heightfield> peakRelief(const PeakParams& p, int width, int height, double meters_per_pixel) {
    auto solved = solvePeakShape(p);
    if (!solved) return solved.status();
    const PeakShape s = *solved;
    Heightfield out(width, height, meters_per_pixel);
    // Beyond t_cut the peak is below 1e-6 of its height: exact zero keeps the layer's support compact.
    const double t_cut = std::pow(std::log(1.0e6), 1.0 / s.beta);
    const double reach = t_cut * std::max({s.scale_forward, s.scale_backward, s.scale_side});
    const double az = p.skew_azimuth_deg * M_PI / 180.0, ca = std::cos(az), sa = std::sin(az);
    const int x0 = std::max(0, static_cast<int>(std::floor(p.center_x - reach)));
    const int x1 = std::min(width, static_cast<int>(std::ceil(p.center_x + reach)) + 1);
    const int y0 = std::max(0, static_cast<int>(std::floor(p.center_y - reach)));
    const int y1 = std::min(height, static_cast<int>(std::ceil(p.center_y + reach)) + 1);
    if (x0 >= x1 || y0 >= y1) return out;
    layers::parallelFor(y1 - y0, 40L * (x1 - x0), [&](int b, int e) {
        for (int y = y0 + b; y < y0 + e; ++y)
            for (int x = x0; x < x1; ++x) {
                const double dx = x - p.center_x, dy = y - p.center_y;
                const double u = dx * ca + dy * sa, v = -dx * sa + dy * ca;
                const double su = u >= 0 ? s.scale_forward : s.scale_backward;
                const double t = std::sqrt((u / su) * (u / su) + (v / s.scale_side) * (v / s.scale_side));
                if (t < t_cut) out.at(x, y) = static_cast<float>(p.height_m * std::exp(-std::pow(t, s.beta)));
            }
    });
    return out;
}

}  // namespace terrasynth
