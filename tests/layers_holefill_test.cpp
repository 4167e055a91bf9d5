// Hole filling by spiral-order quilting with three variants and guided re-synthesis
// (Bradbury et al. 2014 s4.4) on real DEMs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "terrasynth/layers.h"
#include "test_support.h"

namespace terrasynth {
namespace {

std::vector<double> sorted(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v;
}
double pct(const std::vector<double>& s, double q) { return s[static_cast<size_t>(q * (s.size() - 1))]; }

// Height steps between 4-neighbours across the hole boundary, and the same steps between
// neighbours of the surrounding terrain (a ring up to 16 px outside the hole).
struct Steps {
    std::vector<double> boundary, local;
};
Steps steps(const Heightfield& filled, const Heightfield& original, const std::vector<uint8_t>& hole) {
    Steps s;
    const int w = filled.width, h = filled.height;
    std::vector<int> dist(hole.size(), 1 << 20);  // chessboard distance to the hole
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (hole[y * w + x])
                for (int dy = -16; dy <= 16; ++dy)
                    for (int dx = -16; dx <= 16; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx >= 0 && ny >= 0 && nx < w && ny < h)
                            dist[ny * w + nx] = std::min(dist[ny * w + nx], std::max(std::abs(dx), std::abs(dy)));
                    }
    for (int y = 0; y + 1 < h; ++y)
        for (int x = 0; x + 1 < w; ++x)
            for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
                const size_t a = y * w + x, b = (y + dy) * w + (x + dx);
                if (hole[a] != hole[b]) s.boundary.push_back(std::fabs(filled.heights[a] - filled.heights[b]));
                else if (!hole[a] && dist[a] <= 16 && dist[b] <= 16)
                    s.local.push_back(std::fabs(original.heights[a] - original.heights[b]));
            }
    s.boundary = sorted(s.boundary);
    s.local = sorted(s.local);
    return s;
}

class LayersHoleFill : public ::testing::Test {
protected:
    void SetUp() override {
        terrain = test::crop(test::loadExemplarField("orom_rockies"), 150, 150, 256, 256);
        params.hole = Region{RegionShape::Ellipse, 90, 80, 72, 84};
        params.seed = 11;
        hole = holeMask(params, terrain.width, terrain.height);
    }
    void expectNoBoundaryStep(const Heightfield& filled, const char* what) {
        const Steps s = steps(filled, terrain, hole);
        std::printf("%s: boundary step p50 %.1f p99 %.1f max %.1f; local p50 %.1f p99 %.1f max %.1f m\n", what,
                    pct(s.boundary, 0.5), pct(s.boundary, 0.99), s.boundary.back(), pct(s.local, 0.5),
                    pct(s.local, 0.99), s.local.back());
        EXPECT_LE(s.boundary.back(), s.local.back()) << what;
        EXPECT_LE(pct(s.boundary, 0.99), pct(s.local, 0.99)) << what;
        EXPECT_LE(pct(s.boundary, 0.5), 1.5 * pct(s.local, 0.5)) << what;
    }
    Heightfield terrain;
    HoleFillParams params;
    std::vector<uint8_t> hole;
};

TEST_F(LayersHoleFill, FilledHoleHasNoBoundaryStep) {
    auto filled = holeFill(terrain, params);
    ASSERT_TRUE(filled) << filled.message();
    expectNoBoundaryStep(*filled, "quilted");
    // Outside the hole nothing changes.
    for (size_t i = 0; i < hole.size(); ++i) {
        if (hole[i]) continue;
        ASSERT_EQ(filled->heights[i], terrain.heights[i]);
    }
    // And as a layer blended into the stack.
    LayerStack stack;
    EditLayer layer;
    layer.tool = params;
    stack.layers.push_back(layer);
    auto out = applyLayerStack(stack, terrain);
    ASSERT_TRUE(out) << out.message();
    expectNoBoundaryStep(*out, "hole_fill layer");
}

// The same measure catches a flat fill (the hole's rim mean), so the test above can fail.
TEST_F(LayersHoleFill, FlatFillIsCaught) {
    Heightfield flat = terrain;
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < hole.size(); ++i)
        if (!hole[i] && ((i + 1 < hole.size() && hole[i + 1]) || (i > 0 && hole[i - 1]))) sum += terrain.heights[i], ++n;
    for (size_t i = 0; i < hole.size(); ++i)
        if (hole[i]) flat.heights[i] = static_cast<float>(sum / n);
    const Steps s = steps(flat, terrain, hole);
    EXPECT_GT(s.boundary.back(), s.local.back());
}

TEST_F(LayersHoleFill, FillLooksLikeTheTerrainNotABlur) {
    auto filled = holeFill(terrain, params);
    ASSERT_TRUE(filled) << filled.message();
    std::vector<double> inside, around;
    for (int y = 1; y < 255; ++y)
        for (int x = 1; x < 255; ++x) {
            const double g = std::hypot(filled->at(x + 1, y) - filled->at(x - 1, y), filled->at(x, y + 1) - filled->at(x, y - 1));
            (hole[y * 256 + x] ? inside : around).push_back(g);
        }
    double mi = 0, ma = 0;
    for (double g : inside) mi += g;
    for (double g : around) ma += g;
    mi /= inside.size(), ma /= around.size();
    EXPECT_GT(mi, 0.6 * ma);
    EXPECT_LT(mi, 1.5 * ma);
}

TEST_F(LayersHoleFill, ThreeDistinctVariantsAndGuidedResynthesis) {
    auto gen0 = holeFillVariants(terrain, params, 0, nullptr);
    ASSERT_TRUE(gen0) << gen0.message();
    ASSERT_EQ(gen0->size(), 3u);
    auto meanDiff = [&](const Heightfield& a, const Heightfield& b) {
        double s = 0;
        int n = 0;
        for (size_t i = 0; i < hole.size(); ++i)
            if (hole[i]) s += std::fabs(a.heights[i] - b.heights[i]), ++n;
        return s / n;
    };
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b) EXPECT_GT(meanDiff((*gen0)[a], (*gen0)[b]), 5.0) << a << " vs " << b;
    // Re-synthesis from pick 1 keeps its structure (low frequencies) but varies it.
    const Heightfield& pick = (*gen0)[1];
    auto gen1 = holeFillVariants(terrain, params, 1, &pick);
    ASSERT_TRUE(gen1) << gen1.message();
    const BandDecomposition pick_bands = decomposeBands(pick, BandSplit{8, 32});
    for (const Heightfield& v : *gen1) {
        const BandDecomposition vb = decomposeBands(v, BandSplit{8, 32});
        const double to_pick = meanDiff(vb.low, pick_bands.low);
        const double to_others = std::min(meanDiff(vb.low, decomposeBands((*gen0)[0], BandSplit{8, 32}).low),
                                          meanDiff(vb.low, decomposeBands((*gen0)[2], BandSplit{8, 32}).low));
        EXPECT_LT(to_pick, to_others);
        EXPECT_GT(meanDiff(v, pick), 1.0);  // a new variation, not a copy
    }
    // The lineage in the layer reproduces the pick exactly.
    HoleFillParams lineage = params;
    lineage.choices = {1, 2};
    auto final_pick = holeFill(terrain, lineage);
    ASSERT_TRUE(final_pick);
    EXPECT_EQ(final_pick->heights, (*gen1)[2].heights);
}

TEST_F(LayersHoleFill, HoleCoveringTheWholeGridIsAnError) {
    HoleFillParams all = params;
    all.hole = Region{RegionShape::Rect, 0, 0, 256, 256};
    auto r = holeFill(terrain, all);
    ASSERT_FALSE(r);
    EXPECT_NE(r.message().find("hole"), std::string::npos);
}

}  // namespace
}  // namespace terrasynth
