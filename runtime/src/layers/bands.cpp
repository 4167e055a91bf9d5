// Band split of s3.2: three bands over a Laplacian pyramid.
#include <cmath>
#include <string>

#include "layers/pyramid.h"
#include "terrasynth/layers_bands.h"

namespace terrasynth {
namespace {

int log2Exact(int v) {
    int l = 0;
    while ((1 << l) < v) ++l;
    return l;
}
bool isPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }

// Keeps only the levels of one band (the residual counts as low).
layers::Pyramid selectBand(const layers::Pyramid& p, const BandSplit& split, Band band) {
    layers::Pyramid out = p;
    for (int i = 0; i <= p.depth(); ++i) {
        const Band b = i == p.depth() ? Band::Low : split.bandOfLevel(i);
        if (b != band) std::fill(out.levels[i].samples.begin(), out.levels[i].samples.end(), 0.0f);
    }
    return out;
}

}  // namespace

// Level i spans wavelengths ~2^(i+1)..2^(i+2) px, so the cut 2^k ends the band at level k-2.
int BandSplit::highLevels() const { return log2Exact(high_mid_cut_px) - 1; }
int BandSplit::depth() const { return log2Exact(mid_low_cut_px) - 1; }
Band BandSplit::bandOfLevel(int level) const {
    if (level < highLevels()) return Band::High;
    if (level < depth()) return Band::Mid;
    return Band::Low;
}

Status validateBandSplit(const BandSplit& s) {
    if (!isPowerOfTwo(s.high_mid_cut_px) || s.high_mid_cut_px < 4 || s.high_mid_cut_px > 512)
        return Status::error("high_mid_cut_px: must be a power of two in 4..512, got " +
                             std::to_string(s.high_mid_cut_px));
    if (!isPowerOfTwo(s.mid_low_cut_px) || s.mid_low_cut_px > 1024)
        return Status::error("mid_low_cut_px: must be a power of two <= 1024, got " + std::to_string(s.mid_low_cut_px));
    if (s.mid_low_cut_px <= s.high_mid_cut_px)
        return Status::error("mid_low_cut_px: must be above high_mid_cut_px (" + std::to_string(s.high_mid_cut_px) + ")");
    return Status::ok();
}

BandDecomposition decomposeBands(const Heightfield& field, const BandSplit& split) {
    TERRASYNTH_REQUIRE(validateBandSplit(split).isOk(), "invalid band split");
    const layers::Pyramid p = layers::buildLaplacian(layers::toPlane(field), split.depth());
    BandDecomposition d;
    d.low = layers::toField(layers::collapse(selectBand(p, split, Band::Low)), field);
    d.mid = layers::toField(layers::collapse(selectBand(p, split, Band::Mid)), field);
    d.high = layers::toField(layers::collapse(selectBand(p, split, Band::High)), field);
    return d;
}

Heightfield reweightBands(const Heightfield& field, const BandWeights& weights, const BandSplit& split) {
    TERRASYNTH_REQUIRE(validateBandSplit(split).isOk(), "invalid band split");
    layers::Pyramid p = layers::buildLaplacian(layers::toPlane(field), split.depth());
    for (int i = 0; i <= p.depth(); ++i) {
        const float w = weights.get(i == p.depth() ? Band::Low : split.bandOfLevel(i));
        if (w != 1.0f)
            for (float& v : p.levels[i].samples) v *= w;
    }
    return layers::toField(layers::collapse(p), field);
}

}  // namespace terrasynth
