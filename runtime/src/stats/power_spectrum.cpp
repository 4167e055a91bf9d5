// Radially averaged power spectrum by Welch's method and its log-log slope (terrain_stats.h and
// docs/realism.md, "Spectral slope"). Detrending and windowing each tile keep the edges of a
// non-periodic DEM from leaking a spurious f^-2 "cliff" spectrum into every frequency.
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "stats/fft.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {
namespace {

constexpr int kMaxTile = 512;
constexpr int kBinsPerDecade = 10;
constexpr double kFitLowCyclesPerTile = 4.0;
constexpr double kFitHighCyclesPerPixel = 0.25;

int tileSizeFor(int width, int height) {
    int t = 1;
    while (t * 2 <= std::min({width, height, kMaxTile})) t *= 2;
    return t;
}

// Tile origins along one axis: 50% overlap, spread evenly so the last tile ends at the border.
std::vector<int> tileStarts(int length, int tile) {
    const int count = (length - tile + tile / 2 - 1) / (tile / 2) + 1;
    std::vector<int> starts(count, 0);
    for (int i = 1; i < count; ++i)
        starts[i] = static_cast<int>(std::lround(static_cast<double>(i) * (length - tile) / (count - 1)));
    return starts;
}

// Copies a tile, removes its least-squares plane and applies a separable Hann window.
void prepareTile(const Heightfield& f, int x0, int y0, int t, const std::vector<double>& hann,
                 std::vector<std::complex<double>>& out) {
    const double centre = 0.5 * (t - 1);
    double mean = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0;
    for (int y = 0; y < t; ++y)
        for (int x = 0; x < t; ++x) {
            const double z = f.at(x0 + x, y0 + y);
            mean += z;
            sx += z * (x - centre);
            sy += z * (y - centre);
        }
    for (int i = 0; i < t; ++i) sxx += (i - centre) * (i - centre);
    sxx *= t;  // sum over the whole tile of (x - centre)^2; equal for y on a square tile
    mean /= static_cast<double>(t) * t;
    const double bx = sx / sxx, by = sy / sxx;
    for (int y = 0; y < t; ++y)
        for (int x = 0; x < t; ++x) {
            const double z = f.at(x0 + x, y0 + y) - mean - bx * (x - centre) - by * (y - centre);
            out[static_cast<size_t>(y) * t + x] = z * hann[x] * hann[y];
        }
}

void fitSlope(Spectrum& s, double mean_spacing) {
    const double f_lo = kFitLowCyclesPerTile / (s.tile_size * mean_spacing);
    const double f_hi = kFitHighCyclesPerPixel / mean_spacing;
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (size_t i = 0; i < s.power.size(); ++i) {
        if (s.frequency_per_m[i] < f_lo || s.frequency_per_m[i] > f_hi || !(s.power[i] > 0.0)) continue;
        const double x = std::log10(s.frequency_per_m[i]), y = std::log10(s.power[i]);
        n += 1;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
    }
    const double vx = sxx - sx * sx / n, vy = syy - sy * sy / n, cxy = sxy - sx * sy / n;
    if (n < 3 || !(vx > 0.0) || !(vy > 0.0)) {
        s.slope_2d = s.slope_1d = s.hurst = std::numeric_limits<double>::quiet_NaN();
        s.fit_r2 = 0.0;
        return;
    }
    s.slope_2d = cxy / vx;
    s.slope_1d = s.slope_2d + 1.0;
    s.hurst = (-s.slope_2d - 2.0) / 2.0;
    s.fit_r2 = cxy * cxy / (vx * vy);
}

}  // namespace

Result<Spectrum> powerSpectrum(const Heightfield& field) {
    if (field.width < 32 || field.height < 32 || field.heights.size() != field.size() ||
        field.heights.size() != static_cast<size_t>(field.width) * field.height)
        return Status::error("power spectrum needs at least 32x32 samples, got " + std::to_string(field.width) +
                             "x" + std::to_string(field.height));
    Spectrum s;
    const int t = s.tile_size = tileSizeFor(field.width, field.height);
    std::vector<double> hann(t);
    for (int i = 0; i < t; ++i) hann[i] = 0.5 - 0.5 * std::cos(2.0 * 3.14159265358979323846 * (i + 0.5) / t);

    // Periodogram scaled to a power spectral density in m^2 per (cycle/m)^2, averaged over tiles, so
    // levels are comparable between fields of different sizes: |F|^2 * dx * dy / sum(window^2).
    const double lx = field.meters_per_pixel_x, ly = field.meters_per_pixel_y;
    double window_energy = 0.0;
    for (double w : hann) window_energy += w * w;
    window_energy *= window_energy;
    const std::vector<int> xs = tileStarts(field.width, t), ys = tileStarts(field.height, t);
    const double scale = lx * ly / (window_energy * static_cast<double>(xs.size() * ys.size()));
    std::vector<double> power(static_cast<size_t>(t) * t, 0.0);
    std::vector<std::complex<double>> tile(power.size());
    for (int y0 : ys)
        for (int x0 : xs) {
            prepareTile(field, x0, y0, t, hann, tile);
            stats::fft2d(tile, t, /*inverse=*/false);
            for (size_t i = 0; i < power.size(); ++i) power[i] += std::norm(tile[i]) * scale;
        }

    // Annuli of radial frequency, 10 per decade in cycles per (mean) pixel, up to Nyquist.
    const double mean_spacing = std::sqrt(lx * ly);
    const double f0 = 1.0 / t;  // cycles per pixel of the lowest annulus
    const int bins = static_cast<int>(std::ceil(kBinsPerDecade * std::log10(0.5 / f0))) + 1;
    std::vector<double> sum_power(bins, 0.0), sum_log_f(bins, 0.0), count(bins, 0.0);
    for (int ky = 0; ky < t; ++ky)
        for (int kx = 0; kx < t; ++kx) {
            if (kx == 0 && ky == 0) continue;
            const double fx = (kx <= t / 2 ? kx : kx - t) / (t * lx);
            const double fy = (ky <= t / 2 ? ky : ky - t) / (t * ly);
            const double f = std::hypot(fx, fy);
            const double f_pixel = f * mean_spacing;
            if (f_pixel > 0.5) continue;
            const int b = std::clamp(static_cast<int>(std::floor(kBinsPerDecade * std::log10(f_pixel / f0) + 0.5)),
                                     0, bins - 1);
            sum_power[b] += power[static_cast<size_t>(ky) * t + kx];
            sum_log_f[b] += std::log(f);
            count[b] += 1.0;
        }
    for (int b = 0; b < bins; ++b) {
        if (count[b] == 0.0) continue;
        s.frequency_per_m.push_back(std::exp(sum_log_f[b] / count[b]));
        s.power.push_back(sum_power[b] / count[b]);
    }
    fitSlope(s, mean_spacing);
    return s;
}

}  // namespace terrasynth
