// Peaks, ridges and fractal layers of Bradbury et al. 2014 (s3.1, s4.2) on real terrain.
#include <gtest/gtest.h>

#include <cmath>

#include "terrasynth/layers.h"
#include "test_support.h"

namespace terrasynth {
namespace {

EditLayer makeLayer(ToolParams tool) {
    EditLayer l;
    l.weights = defaultWeights(tool);
    l.tool = std::move(tool);
    return l;
}

Heightfield applyOne(const Heightfield& terrain, EditLayer layer) {
    LayerStack stack;
    stack.layers.push_back(std::move(layer));
    auto out = applyLayerStack(stack, terrain);
    EXPECT_TRUE(out) << out.message();
    return out ? *out : terrain;
}

Heightfield difference(const Heightfield& a, const Heightfield& b) {
    Heightfield d = a;
    for (size_t i = 0; i < d.heights.size(); ++i) d.heights[i] -= b.heights[i];
    return d;
}

TEST(LayersPeak, HeightAndFootprintMatchParametersOnRealTerrain) {
    const Heightfield terrain = test::crop(test::loadExemplarField("orom_appalachians"), 200, 200, 256, 256);
    PeakParams p;
    p.center_x = 128, p.center_y = 120, p.height_m = 650.0, p.spread_px = 18.0;
    const Heightfield delta = difference(applyOne(terrain, makeLayer(p)), terrain);
    // Summit: the full height, at the centre.
    EXPECT_NEAR(delta.at(128, 120), 650.0, 650.0 * 1e-3);
    float top = -1e9f;
    int tx = 0, ty = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            if (delta.at(x, y) > top) top = delta.at(x, y), tx = x, ty = y;
    EXPECT_EQ(tx, 128);
    EXPECT_EQ(ty, 120);
    // Footprint: where the peak exceeds 1% of its height is a disk of the predicted radius.
    const PeakShape shape = *solvePeakShape(p);
    const double r = peakFootprintRadius(p, shape, 0.01);
    EXPECT_NEAR(r, 18.0 * std::sqrt(2.0 * std::log(100.0)), 1e-6);  // a Gaussian: sigma*sqrt(2 ln 100)
    int inside = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            if (delta.at(x, y) >= 0.01 * 650.0) {
                ++inside;
                EXPECT_LE(std::hypot(x - 128.0, y - 120.0), r + 1.0);
            }
    EXPECT_NEAR(inside, M_PI * r * r, 0.03 * M_PI * r * r);
    // Far from it the terrain is untouched.
    EXPECT_LT(std::fabs(delta.at(10, 10)), 1e-2);
    EXPECT_LT(std::fabs(delta.at(250, 250)), 1e-2);
}

// The cross-section along the skew axis, read as a distribution, has exactly the requested moments.
TEST(LayersPeak, CrossSectionMomentsMatchSpreadSkewnessAndKurtosis) {
    struct Case {
        double skew, kurt, azimuth;
    } cases[] = {{0.0, 0.0, 0.0}, {0.5, 1.0, 0.0}, {-0.4, 2.0, 90.0}, {0.3, -0.5, 90.0}, {0.0, -1.0, 0.0}};
    for (const Case& c : cases) {
        PeakParams p;
        p.center_x = 400, p.center_y = 400, p.height_m = 100, p.spread_px = 30, p.skewness = c.skew,
        p.kurtosis = c.kurt, p.skew_azimuth_deg = c.azimuth;
        auto relief = peakRelief(p, 801, 801, 10.0);
        ASSERT_TRUE(relief) << relief.message();
        double m0 = 0, m1 = 0;
        std::vector<double> h(801);
        for (int t = 0; t < 801; ++t) {
            h[t] = c.azimuth == 0.0 ? relief->at(t, 400) : relief->at(400, t);
            m0 += h[t], m1 += h[t] * (t - 400);
        }
        const double mean = m1 / m0;
        double m2 = 0, m3 = 0, m4 = 0;
        for (int t = 0; t < 801; ++t) {
            const double d = t - 400 - mean;
            m2 += h[t] * d * d, m3 += h[t] * d * d * d, m4 += h[t] * d * d * d * d;
        }
        m2 /= m0, m3 /= m0, m4 /= m0;
        EXPECT_NEAR(std::sqrt(m2), 30.0, 0.3) << c.skew << " " << c.kurt;
        EXPECT_NEAR(m3 / std::pow(m2, 1.5), c.skew, 0.02) << c.skew << " " << c.kurt;
        EXPECT_NEAR(m4 / (m2 * m2) - 3.0, c.kurt, 0.05) << c.skew << " " << c.kurt;
        EXPECT_NEAR(relief->at(400, 400), 100.0, 1e-4);
    }
}

TEST(LayersPeak, InvalidParametersNameTheField) {
    PeakParams p;
    p.spread_px = 0;
    EXPECT_NE(solvePeakShape(p).message().find("spread_px"), std::string::npos);
    p.spread_px = 10, p.skewness = 0.8, p.kurtosis = -1.0;
    EXPECT_NE(solvePeakShape(p).message().find("kurtosis"), std::string::npos);
}

TEST(LayersRidge, LowBandRidgeKeepsTheTerrainsDetail) {
    const Heightfield terrain = test::crop(test::loadExemplarField("orom_rockies"), 100, 100, 384, 384);
    RidgeParams r;
    r.points = {{60, 200}, {190, 170}, {320, 200}};  // equal segments: the vertex is mid-profile
    r.profile_m = {300, 600, 300};
    r.width_px = 40;
    EditLayer ridge = makeLayer(r);
    EXPECT_EQ(ridge.weights, (BandWeights{1, 0, 0}));  // s4.2: low band only by default
    const Heightfield out = applyOne(terrain, ridge);
    const Heightfield delta = difference(out, terrain);
    // The raised crest follows the profile (a wide ridge lives almost entirely in the low band).
    EXPECT_NEAR(delta.at(190, 170), 600.0, 0.08 * 600.0);
    EXPECT_NEAR(delta.at(125, 185), 450.0, 0.1 * 450.0);
    // Mid and high bands of the result are the terrain's own: "higher frequencies are taken from the
    // original terrain".
    const BandDecomposition before = decomposeBands(terrain), after = decomposeBands(out);
    double worst = 0, scale = 0;
    for (size_t i = 0; i < before.high.heights.size(); ++i) {
        worst = std::max(worst, double(std::fabs(after.high.heights[i] - before.high.heights[i])));
        scale = std::max(scale, double(std::fabs(before.high.heights[i])));
    }
    EXPECT_LT(worst, 0.01 * scale);
    // With every band on, the crest is exactly the sketched profile.
    ridge.weights = BandWeights{};
    const Heightfield full = difference(applyOne(terrain, ridge), terrain);
    EXPECT_NEAR(full.at(190, 170), 600.0, 1.0);
    EXPECT_NEAR(full.at(60, 200), 300.0, 1.0);
    EXPECT_NEAR(full.at(190, 170 + 40), 600.0 * std::exp(-0.5), 15.0);  // one width off the crest
}

TEST(LayersFractal, SeededAndDeterministic) {
    for (FractalKind kind : {FractalKind::Fbm, FractalKind::DiamondSquare}) {
        FractalParams f;
        f.kind = kind;
        f.seed = 42;
        f.amplitude_m = 300;
        const Heightfield a = fractalHeightfield(f, 300, 200, 30.0);
        const Heightfield b = fractalHeightfield(f, 300, 200, 30.0);
        EXPECT_EQ(a.heights, b.heights);
        f.seed = 43;
        const Heightfield c = fractalHeightfield(f, 300, 200, 30.0);
        EXPECT_NE(a.heights, c.heights);
        const HeightRange r = heightRange(a);
        EXPECT_GT(r.max - r.min, 100.0);  // real relief
        EXPECT_LE(std::max(std::fabs(r.max), std::fabs(r.min)), 300.0 * 1.01);
    }
}

TEST(LayersFractal, RegionNoiseStaysInsideItsRegion) {
    const Heightfield terrain = test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 256, 256);
    NoiseParams n;
    n.fractal.amplitude_m = 80;
    n.region = Region{RegionShape::Ellipse, 60, 60, 120, 120};
    n.feather_px = 20;
    const Heightfield delta = difference(applyOne(terrain, makeLayer(n)), terrain);
    double inside = 0, outside = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            const double d = std::hypot(x - 119.5, y - 119.5);
            if (d < 40) inside = std::max(inside, double(std::fabs(delta.at(x, y))));
            if (d > 75) outside = std::max(outside, double(std::fabs(delta.at(x, y))));
        }
    EXPECT_GT(inside, 10.0);
    EXPECT_LT(outside, 1e-2);
}

}  // namespace
}  // namespace terrasynth
