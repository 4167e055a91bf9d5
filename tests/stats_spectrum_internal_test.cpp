// The FFT against a direct DFT, and the spectral slope: recovered Hurst exponents of synthetic
// fractional Brownian surfaces, white noise, and the band real mountain DEMs fall in.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "stats/fft.h"
#include "terrasynth/terrain_stats.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Fractional Brownian surface by spectral synthesis: amplitude ~ f^-(H+1), i.e. 2D power ~ f^-(2H+2),
// random phases, on a periodic n x n grid; the caller crops an interior window so the periodicity
// (which the estimator never sees) does not help it.
Heightfield fbmSurface(int n, double hurst, double spacing, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::vector<std::complex<double>> spectrum(static_cast<size_t>(n) * n);
    for (int ky = 0; ky < n; ++ky)
        for (int kx = 0; kx < n; ++kx) {
            const double fx = kx <= n / 2 ? kx : kx - n, fy = ky <= n / 2 ? ky : ky - n;
            const double f = std::hypot(fx, fy);
            if (f == 0.0) continue;
            const double amplitude = std::pow(f, -(hurst + 1.0));
            spectrum[static_cast<size_t>(ky) * n + kx] = amplitude * std::complex<double>(gauss(rng), gauss(rng));
        }
    stats::fft2d(spectrum, n, /*inverse=*/true);
    Heightfield field(n, n, spacing);
    double lo = 1e300, hi = -1e300;
    for (const auto& c : spectrum) lo = std::min(lo, c.real()), hi = std::max(hi, c.real());
    // Real part only (the Hermitian symmetry is not imposed; the real part of a random-phase field is
    // itself a random-phase field with the same power law). Scale to 1000 m of relief.
    for (size_t i = 0; i < field.size(); ++i) field.heights[i] = static_cast<float>(1000.0 * (spectrum[i].real() - lo) / (hi - lo));
    return field;
}

}  // namespace

TEST(StatsFft, MatchesDirectDftAndInvertsExactly) {
    const int n = 32;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<std::complex<double>> x(n), X(n);
    for (auto& v : x) v = {u(rng), u(rng)};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j) X[k] += x[j] * std::polar(1.0, -2.0 * kPi * k * j / n);
    std::vector<std::complex<double>> y = x;
    stats::fft(y.data(), n, false);
    for (int k = 0; k < n; ++k) EXPECT_LT(std::abs(y[k] - X[k]), 1e-12);
    stats::fft(y.data(), n, true);
    for (int k = 0; k < n; ++k) EXPECT_LT(std::abs(y[k] - x[k]), 1e-14);
}

TEST(StatsSpectrum, RecoversTheHurstExponentOfFractionalBrownianSurfaces) {
    for (double hurst : {0.3, 0.5, 0.8}) {
        const Heightfield fbm = test::crop(fbmSurface(1024, hurst, 30.0, 17), 200, 300, 600, 600);
        auto s = powerSpectrum(fbm);
        ASSERT_TRUE(s) << s.message();
        EXPECT_EQ(s->tile_size, 512);
        EXPECT_NEAR(s->hurst, hurst, 0.06) << "slope_2d " << s->slope_2d;
        EXPECT_NEAR(s->slope_1d, -(2.0 * hurst + 1.0), 0.12);
        EXPECT_GT(s->fit_r2, 0.97);
        // The PSD is in m^2/(cycle/m)^2 and falls with frequency.
        EXPECT_GT(s->power.front(), 100.0 * s->power.back());
    }
}

TEST(StatsSpectrum, WhiteNoiseIsFlatAndRealMountainsAreRed) {
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss(0.0f, 10.0f);
    Heightfield noise(300, 300, 92.6);
    for (float& z : noise.heights) z = 500.0f + gauss(rng);
    auto white = powerSpectrum(noise);
    ASSERT_TRUE(white) << white.message();
    EXPECT_EQ(white->tile_size, 256);
    EXPECT_NEAR(white->slope_2d, 0.0, 0.2);

    // Mountain topography has 1D spectral slopes around -2 (Brownian) to -3 (smooth at this scale).
    for (const char* stem : {"orom_alaska", "orom_himalaya-everest", "orom_rockies", "orom_appalachians"}) {
        auto s = powerSpectrum(test::loadExemplarField(stem));
        ASSERT_TRUE(s) << s.message();
        EXPECT_LT(s->slope_1d, -1.8) << stem;
        EXPECT_GT(s->slope_1d, -3.6) << stem;
        EXPECT_GT(s->fit_r2, 0.9) << stem;
    }
}

TEST(StatsSpectrum, AnisotropicSpacingIsHonoured) {
    // Squeezing the same fBm onto cells twice as long in y must not change its exponent much, because
    // frequencies are measured in cycles per metre along each axis.
    Heightfield fbm = test::crop(fbmSurface(1024, 0.6, 30.0, 23), 100, 100, 512, 512);
    auto iso = powerSpectrum(fbm);
    fbm.meters_per_pixel_y = 60.0;
    auto aniso = powerSpectrum(fbm);
    ASSERT_TRUE(iso && aniso);
    EXPECT_NEAR(aniso->slope_2d, iso->slope_2d, 0.25);
    EXPECT_LT(aniso->frequency_per_m.front(), iso->frequency_per_m.front() * 1.01);
}
