// Texture transfer (Bradbury et al. 2014 s4.3): copy-paste from an external DEM or the terrain itself,
// blended in the Laplacian pyramid with max-gradient selection, on real DEMs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "terrasynth/layers.h"
#include "test_support.h"

namespace terrasynth {
namespace {

double gradientAt(const Heightfield& f, int x, int y) {
    const double gx = 0.5 * (f.at(x + 1, y) - f.at(x - 1, y)), gy = 0.5 * (f.at(x, y + 1) - f.at(x, y - 1));
    return std::hypot(gx, gy);
}

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<size_t>(q * (v.size() - 1))];
}

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / v.size();
}

// Gradient magnitudes on the ellipse's boundary (within 1.5 px of it) and in the interiors on either
// side (more than `margin` px from it).
struct SeamSample {
    std::vector<double> boundary, interior;
};
SeamSample sampleSeam(const Heightfield& f, const Region& r, double margin) {
    SeamSample s;
    const double cx = r.x + (r.width - 1) / 2, cy = r.y + (r.height - 1) / 2, a = r.width / 2, b = r.height / 2;
    for (int y = 1; y < f.height - 1; ++y)
        for (int x = 1; x < f.width - 1; ++x) {
            const double d = (1.0 - std::hypot((x - cx) / a, (y - cy) / b)) * std::min(a, b);  // > 0 inside
            if (std::fabs(d) < 1.5) s.boundary.push_back(gradientAt(f, x, y));
            else if (std::fabs(d) > margin) s.interior.push_back(gradientAt(f, x, y));
        }
    return s;
}

// "No seam": the boundary's gradients lie within the interiors' distribution (a naive cut-and-paste
// puts its boundary mean beyond the interiors' 99th percentile, see below).
void expectSeamless(const SeamSample& s, const char* what) {
    const double b_mean = mean(s.boundary), b_p95 = percentile(s.boundary, 0.95);
    std::printf("%s: boundary mean %.1f p95 %.1f; interior p50 %.1f p75 %.1f p90 %.1f p99 %.1f\n", what, b_mean, b_p95,
                percentile(s.interior, 0.5), percentile(s.interior, 0.75), percentile(s.interior, 0.9),
                percentile(s.interior, 0.99));
    EXPECT_LE(b_mean, percentile(s.interior, 0.90)) << what;
    EXPECT_LE(b_p95, percentile(s.interior, 0.99)) << what;
    EXPECT_GE(b_mean, percentile(s.interior, 0.05)) << what;
}

class LayersPaste : public ::testing::Test {
protected:
    void SetUp() override {
        dest = test::crop(test::loadExemplarField("orom_appalachians"), 100, 100, 384, 384);
        source_path = test::dataDir() + "/exemplars/orom_himalaya-everest.png";
        source = test::loadExemplarField("orom_himalaya-everest");
        paste.source = source_path;
        paste.source_x = 220, paste.source_y = 180;
        paste.dest = Region{RegionShape::Ellipse, 110, 100, 170, 190};
    }
    Heightfield apply(const PasteParams& p, BandWeights w = {}) {
        LayerStack stack;
        EditLayer l;
        l.tool = p;
        l.weights = w;
        stack.layers.push_back(l);
        auto out = applyLayerStack(stack, dest);
        EXPECT_TRUE(out) << out.message();
        return out ? *out : dest;
    }
    Heightfield dest, source;
    std::string source_path;
    PasteParams paste;
};

TEST_F(LayersPaste, ExternalDemPasteHasNoSeam) {
    const Heightfield out = apply(paste);
    expectSeamless(sampleSeam(out, paste.dest, 24.0), "max-gradient paste");
    // The pasted relief is really there: max-gradient keeps, per coefficient, the stronger of source
    // and destination, so the region's detail is at least as strong as either's.
    auto detail = [](const Heightfield& f, int x0, int y0) {
        const BandDecomposition d = decomposeBands(f);
        double sum = 0;
        for (int y = 0; y < 60; ++y)
            for (int x = 0; x < 60; ++x) sum += std::fabs(d.mid.at(x0 + x, y0 + y)) + std::fabs(d.high.at(x0 + x, y0 + y));
        return sum;
    };
    const double out_detail = detail(out, 165, 165), dest_detail = detail(dest, 165, 165);
    const double src_detail = detail(source, 220 + 55, 180 + 65);
    EXPECT_GT(out_detail, 0.9 * std::max(dest_detail, src_detail));
    PasteParams replace = paste;
    replace.blend = PasteBlend::Replace;
    expectSeamless(sampleSeam(apply(replace), paste.dest, 24.0), "replace paste");
}

// The same measure catches the seam a naive cut-and-paste (mean-matched, no blending) leaves, so the
// test above can fail.
TEST_F(LayersPaste, NaiveCutAndPasteIsCaughtAsASeam) {
    Heightfield naive = dest;
    const std::vector<float> mask = regionMask(paste.dest, 0.0, dest.width, dest.height);
    double sum_m = 0, src = 0, dst = 0;
    for (int y = 0; y < dest.height; ++y)
        for (int x = 0; x < dest.width; ++x) {
            const double m = mask[y * dest.width + x] >= 0.5 ? 1 : 0;
            sum_m += m;
            src += m * source.at(220 + x - 110, 180 + y - 100);
            dst += m * dest.at(x, y);
        }
    for (int y = 0; y < dest.height; ++y)
        for (int x = 0; x < dest.width; ++x)
            if (mask[y * dest.width + x] >= 0.5)
                naive.at(x, y) = static_cast<float>(source.at(220 + x - 110, 180 + y - 100) - src / sum_m + dst / sum_m);
    const SeamSample s = sampleSeam(naive, paste.dest, 24.0);
    std::printf("naive: boundary mean %.1f p95 %.1f; interior p75 %.1f p90 %.1f p99 %.1f\n", mean(s.boundary),
                percentile(s.boundary, 0.95), percentile(s.interior, 0.75), percentile(s.interior, 0.9),
                percentile(s.interior, 0.99));
    EXPECT_GT(mean(s.boundary), percentile(s.interior, 0.99));
}

// s4.3/Figure 6: the frequency decomposition lets the artist discard the pasted low frequencies and
// transfer only detail.
TEST_F(LayersPaste, DiscardingTheLowBandTransfersOnlyDetail) {
    PasteParams raw = paste;
    raw.match_height = false;  // keep the Himalayan heights: 4-5 km above the Appalachians
    const Heightfield detail_only = apply(raw, BandWeights{0, 1, 1});
    const Heightfield everything = apply(raw);
    auto regionMean = [](const Heightfield& f) {
        double s = 0;
        for (int y = 165; y < 225; ++y)
            for (int x = 165; x < 225; ++x) s += f.at(x, y);
        return s / 3600.0;
    };
    const double lift_all = regionMean(everything) - regionMean(dest);
    const double lift_detail = regionMean(detail_only) - regionMean(dest);
    EXPECT_GT(lift_all, 3000.0);                      // the whole source came along ...
    EXPECT_LT(std::fabs(lift_detail), 0.05 * lift_all);  // ... but without its low band the terrain stays put
    // while its detail does arrive: the region differs from the destination by more than a few metres.
    double change = 0;
    for (int y = 165; y < 225; ++y)
        for (int x = 165; x < 225; ++x) change += std::fabs(detail_only.at(x, y) - dest.at(x, y));
    EXPECT_GT(change / 3600.0, 50.0);
}

TEST_F(LayersPaste, SourceOutsideTheDemIsAnErrorNamingTheLayer) {
    PasteParams bad = paste;
    bad.source_x = 600;
    LayerStack stack;
    EditLayer l;
    l.tool = bad;
    stack.layers.push_back(l);
    auto out = applyLayerStack(stack, dest);
    ASSERT_FALSE(out);
    EXPECT_NE(out.message().find("layers[1].source_x"), std::string::npos) << out.message();
}

TEST_F(LayersPaste, CopyFromTheTerrainItself) {
    PasteParams clone;
    clone.source = "terrain";
    clone.source_x = 20, clone.source_y = 200;
    clone.dest = Region{RegionShape::Ellipse, 220, 40, 120, 120};
    const Heightfield out = apply(clone);
    expectSeamless(sampleSeam(out, clone.dest, 20.0), "terrain clone");
    // The clone's detail is the source area's: compare high bands at the centre.
    const BandDecomposition d = decomposeBands(out), s = decomposeBands(dest);
    double corr = 0, na = 0, nb = 0;
    for (int y = 80; y < 120; ++y)
        for (int x = 260; x < 300; ++x) {
            const double a = d.high.at(x, y), b = s.high.at(x - 200, y + 160);
            corr += a * b, na += a * a, nb += b * b;
        }
    EXPECT_GT(corr / std::sqrt(na * nb), 0.5);
}

}  // namespace
}  // namespace terrasynth
