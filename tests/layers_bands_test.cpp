// Band decomposition of Bradbury et al. 2014 s3.2 on real DEMs: exact recomposition, and each band
// holding the frequencies its cut says (checked on the Fourier spectrum).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "terrasynth/layers.h"
#include "test_support.h"

namespace terrasynth {
namespace {

double relief(const Heightfield& f) {
    const HeightRange r = heightRange(f);
    return r.max - r.min;
}

double maxAbsDiff(const Heightfield& a, const Heightfield& b) {
    double m = 0;
    for (size_t i = 0; i < a.heights.size(); ++i) m = std::max(m, std::fabs(double(a.heights[i]) - b.heights[i]));
    return m;
}

// In-place radix-2 FFT.
void fft(std::vector<std::complex<double>>& a) {
    const size_t n = a.size();
    for (size_t i = 1, j = 0; i < n; ++i) {
        size_t bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) std::swap(a[i], a[j]);
    }
    for (size_t len = 2; len <= n; len <<= 1) {
        const std::complex<double> wl = std::polar(1.0, -2 * M_PI / len);
        for (size_t i = 0; i < n; i += len) {
            std::complex<double> w = 1;
            for (size_t k = 0; k < len / 2; ++k, w *= wl) {
                const auto u = a[i + k], v = a[i + k + len / 2] * w;
                a[i + k] = u + v;
                a[i + k + len / 2] = u - v;
            }
        }
    }
}

// Power spectrum of a Hann-windowed, mean-removed square power-of-two field, keyed by the larger
// of the two axis frequencies (cycles per pixel).
struct Spectrum {
    std::vector<double> freq, power;
    double energy(double lo, double hi) const {
        double e = 0;
        for (size_t i = 0; i < freq.size(); ++i)
            if (freq[i] >= lo && freq[i] < hi) e += power[i];
        return e;
    }
};
Spectrum spectrum(const Heightfield& f) {
    const int n = f.width;
    double mean = 0;
    for (float v : f.heights) mean += v;
    mean /= f.heights.size();
    std::vector<std::complex<double>> g(static_cast<size_t>(n) * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double w = (0.5 - 0.5 * std::cos(2 * M_PI * (x + 0.5) / n)) * (0.5 - 0.5 * std::cos(2 * M_PI * (y + 0.5) / n));
            g[static_cast<size_t>(y) * n + x] = w * (f.at(x, y) - mean);
        }
    std::vector<std::complex<double>> line(n);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) line[x] = g[static_cast<size_t>(y) * n + x];
        fft(line);
        for (int x = 0; x < n; ++x) g[static_cast<size_t>(y) * n + x] = line[x];
    }
    for (int x = 0; x < n; ++x) {
        for (int y = 0; y < n; ++y) line[y] = g[static_cast<size_t>(y) * n + x];
        fft(line);
        for (int y = 0; y < n; ++y) g[static_cast<size_t>(y) * n + x] = line[y];
    }
    Spectrum s;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double fx = (x <= n / 2 ? x : x - n) / double(n), fy = (y <= n / 2 ? y : y - n) / double(n);
            // Separable pyramids cut each axis: "above the cut" means along either axis.
            s.freq.push_back(std::max(std::fabs(fx), std::fabs(fy)));
            s.power.push_back(std::norm(g[static_cast<size_t>(y) * n + x]));
        }
    return s;
}

TEST(LayersBands, UnitWeightsReproduceEveryShippedExemplar) {
    for (const char* stem : {"orom_alaska", "orom_appalachians", "orom_himalaya-everest", "orom_rockies"}) {
        const Heightfield f = test::loadExemplarField(stem);
        const Heightfield back = reweightBands(f, BandWeights{});
        EXPECT_LE(maxAbsDiff(f, back), 1e-4 * relief(f)) << stem;
        // The three sub-layers shown to the artist add up to the layer.
        const BandDecomposition d = decomposeBands(f);
        Heightfield sum = d.low;
        for (size_t i = 0; i < sum.heights.size(); ++i) sum.heights[i] += d.mid.heights[i] + d.high.heights[i];
        EXPECT_LE(maxAbsDiff(f, sum), 1e-4 * relief(f)) << stem;
        // And each band is genuinely non-trivial on real terrain.
        for (const Heightfield* b : {&d.mid, &d.high}) EXPECT_GT(relief(*b), 1e-3 * relief(f)) << stem;
    }
}

TEST(LayersBands, StackWithUnitWeightsReproducesImportedHeightmap) {
    const Heightfield f = test::loadExemplarField("orom_himalaya-everest");
    LayerStack stack;
    stack.base.source = BaseSource::Heightmap;
    stack.base.path = test::dataDir() + "/exemplars/orom_himalaya-everest.png";
    auto out = applyLayerStack(stack, Heightfield(f.width, f.height, f.meters_per_pixel_x));
    ASSERT_TRUE(out) << out.message();
    EXPECT_LE(maxAbsDiff(f, *out), 1e-4 * relief(f));
}

TEST(LayersBands, ZeroingHighBandRemovesEnergyAboveTheCut) {
    const Heightfield f = test::crop(test::loadExemplarField("orom_rockies"), 100, 100, 256, 256);
    const BandSplit split;  // cut between high and mid at 8 px: 1/8 cycle per pixel
    const double cut = 1.0 / split.high_mid_cut_px;
    const Heightfield smooth = reweightBands(f, BandWeights{1, 1, 0}, split);
    const Spectrum before = spectrum(f), after = spectrum(smooth);
    const double above_before = before.energy(cut, 1.0), above_after = after.energy(cut, 1.0);
    ASSERT_GT(above_before, 0.0);
    std::printf("energy kept: above cut %.4f, above 1.25 cut %.4f, above 1.5 cut %.5f\n", above_after / above_before,
                after.energy(1.25 * cut, 1.0) / before.energy(1.25 * cut, 1.0),
                after.energy(1.5 * cut, 1.0) / before.energy(1.5 * cut, 1.0));
    // The pyramid's transition band is about a quarter octave wide: above the cut over 90% of the
    // energy goes, a quarter octave above it 95%, half an octave above it 99%.
    EXPECT_LT(above_after / above_before, 0.10);
    EXPECT_LT(after.energy(1.25 * cut, 1.0) / before.energy(1.25 * cut, 1.0), 0.05);
    EXPECT_LT(after.energy(1.5 * cut, 1.0) / before.energy(1.5 * cut, 1.0), 0.01);
    // Wavelengths well above the cut are untouched (within the window's leakage).
    const double low_ratio = after.energy(0.0, cut / 4) / before.energy(0.0, cut / 4);
    EXPECT_NEAR(low_ratio, 1.0, 0.02);
}

TEST(LayersBands, EachBandLivesInItsFrequencyRange) {
    const Heightfield f = test::crop(test::loadExemplarField("orom_alaska"), 64, 64, 256, 256);
    const BandSplit split;
    const BandDecomposition d = decomposeBands(f, split);
    const Spectrum low = spectrum(d.low), high = spectrum(d.high);
    const double lo_cut = 1.0 / split.mid_low_cut_px, hi_cut = 1.0 / split.high_mid_cut_px;
    // Low band: its energy is concentrated below about twice its cut frequency.
    EXPECT_GT(low.energy(0.0, 2 * lo_cut) / low.energy(0.0, 1.0), 0.95);
    // High band: almost nothing at wavelengths far longer than its cut.
    EXPECT_LT(high.energy(0.0, hi_cut / 4) / high.energy(0.0, 1.0), 0.01);
}

TEST(LayersBands, BandSplitValidationNamesTheCut) {
    EXPECT_NE(validateBandSplit({8, 60}).message().find("mid_low_cut_px"), std::string::npos);
    EXPECT_NE(validateBandSplit({3, 64}).message().find("high_mid_cut_px"), std::string::npos);
    EXPECT_FALSE(validateBandSplit({64, 64}));
    EXPECT_TRUE(validateBandSplit({4, 1024}));
}

}  // namespace
}  // namespace terrasynth
