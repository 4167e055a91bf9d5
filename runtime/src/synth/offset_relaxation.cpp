// Offset relaxation: weighted Jacobi iterations on V, S fixed (offset_relaxation.h).
//
// The region is relaxed in bands of rows, each with `iterations` rows of halo on either side: a
// halo row's result is spoiled only where the band's cut removed its neighbours, and after k
// iterations the spoil has moved k rows in, so the band's own rows come out exactly as if the whole
// region had been relaxed at once. Bands bound the scratch memory (about 50 bytes per pixel of a
// band) and are independent, so workers take whole bands and the result does not depend on their
// number.
#include "synth/offset_relaxation.h"

#include <algorithm>
#include <cmath>

#include "core/workers.h"

namespace terrasynth::synth {
namespace {

// The four "forward" neighbours; a pixel's other four are the forward neighbours of the pixels
// behind it, so a pair's weight and shift are stored once, at its first pixel. Seen from q the
// pair's target is exactly the negation of that seen from p (IEEE negation is exact), so the
// stored half is the whole energy.
constexpr int kForward = 4;
constexpr int kDx[kForward] = {1, 0, 1, -1}, kDy[kForward] = {0, 1, 1, 1};

// Rows of a band (its halo comes on top).
constexpr int kBandRows = 128;

// A band's planes, row-major with a ring of one zero pixel so no neighbour read needs a test: the
// ring's weights are 0, and so are those of pairs whose second pixel is outside the region.
struct BandScratch {
    int stride = 0;
    std::vector<float> weight[kForward], shift[kForward];  // shift c_pq: p wants V_q - c, q wants V_p + c
    std::vector<float> held, total, from, to;               // V before relaxing; eps + sum of weights
    std::vector<size_t> fixed;                              // the band's pixels that keep their V
    std::vector<int> source;                                // atlas index of S, per band pixel (no ring)

    void reset(int width, int rows) {
        stride = width + 2;
        const size_t n = static_cast<size_t>(stride) * (rows + 2);
        for (int k = 0; k < kForward; ++k) {
            weight[k].assign(n, 0.0f);
            shift[k].assign(n, 0.0f);
        }
        held.assign(n, 0.0f);
        total.assign(n, 0.0f);
        from.assign(n, 0.0f);
        to.assign(n, 0.0f);
        fixed.clear();
    }
};

int atlasIndex(const DatabaseLevel& db, const PixelState& s) {
    return static_cast<int>(std::lround(s.y)) * db.width + static_cast<int>(std::lround(s.x));
}

// One Jacobi iteration over the `width` pixels of a band row starting at `row`. The four directions
// are spelled out so the loop vectorises: one lane per pixel, each adding its terms in this order.
void relaxRow(int width, size_t row, const ptrdiff_t* offset, const float* __restrict w0, const float* __restrict w1,
              const float* __restrict w2, const float* __restrict w3, const float* __restrict c0,
              const float* __restrict c1, const float* __restrict c2, const float* __restrict c3,
              const float* __restrict held, const float* __restrict total, const float* __restrict from,
              float* __restrict to) {
    const ptrdiff_t o0 = offset[0], o1 = offset[1], o2 = offset[2], o3 = offset[3];
    const ptrdiff_t end = static_cast<ptrdiff_t>(row) + width;
    for (ptrdiff_t b = static_cast<ptrdiff_t>(row); b < end; ++b) {
        float sum = kRelaxOffsetStiffness * held[b];
        // Pairs stored here: p wants V_q - c.
        sum += w0[b] * (from[b + o0] - c0[b]);
        sum += w1[b] * (from[b + o1] - c1[b]);
        sum += w2[b] * (from[b + o2] - c2[b]);
        sum += w3[b] * (from[b + o3] - c3[b]);
        // Pairs stored behind: p is their q, wants V + c.
        sum += w0[b - o0] * (from[b - o0] + c0[b - o0]);
        sum += w1[b - o1] * (from[b - o1] + c1[b - o1]);
        sum += w2[b - o2] * (from[b - o2] + c2[b - o2]);
        sum += w3[b - o3] * (from[b - o3] + c3[b - o3]);
        to[b] = sum / total[b];
    }
}

// Relaxes region rows [y0, y1) with rows [ys, ye) loaded (the halo), writing V of [y0, y1) to `out`.
void relaxBand(const DatabaseLevel& db, const LevelRegion& region, float gentle, int iterations,
               const std::vector<uint8_t>& fixed, const PixelState* state, int y0, int y1, int ys, int ye,
               BandScratch& band, float* out) {
    const int w = region.width, rows = ye - ys;
    const float* e = db.height_m.data();
    band.reset(w, rows);
    const int stride = band.stride;
    auto at = [&](int x, int band_row) { return static_cast<size_t>(band_row + 1) * stride + (x + 1); };
    band.source.resize(static_cast<size_t>(rows) * w);
    for (int r = 0; r < rows; ++r)
        for (int x = 0; x < w; ++x) {
            const size_t p = static_cast<size_t>(ys + r) * w + x, b = at(x, r);
            band.held[b] = band.from[b] = state[p].v;
            if (fixed[p]) band.fixed.push_back(b);
            band.source[static_cast<size_t>(r) * w + x] = atlasIndex(db, state[p]);
        }
    for (int r = 0; r < rows; ++r)
        for (int x = 0; x < w; ++x) {
            const size_t b = at(x, r), here = static_cast<size_t>(r) * w + x;
            const int sp = band.source[here];
            for (int k = 0; k < kForward; ++k) {
                const int qx = x + kDx[k], qr = r + kDy[k];
                if (qx < 0 || qx >= w || qr >= rows) continue;
                const int sq = band.source[here + static_cast<size_t>(kDy[k]) * w + kDx[k]];
                const int d = kDy[k] * db.width + kDx[k];
                // The exemplar's step from S_p towards q and from S_q back towards p, averaged.
                const float target = 0.5f * ((e[sp + d] - e[sp]) + (e[sq] - e[sq - d]));
                const bool diagonal = kDx[k] != 0 && kDy[k] != 0;
                const float sigma = diagonal ? gentle * 1.41421356f : gentle;
                const float falloff = sigma * sigma / (target * target + sigma * sigma);
                band.weight[k][b] = diagonal ? 0.5f * falloff : falloff;
                band.shift[k][b] = target - (e[sq] - e[sp]);
            }
        }
    ptrdiff_t offset[kForward];
    for (int k = 0; k < kForward; ++k) offset[k] = static_cast<ptrdiff_t>(kDy[k]) * stride + kDx[k];
    // eps + the weights of a pixel's 8 pairs, in the order the iterations add them.
    for (int r = 0; r < rows; ++r)
        for (int x = 0; x < w; ++x) {
            const size_t b = at(x, r);
            float total = kRelaxOffsetStiffness;
            for (int k = 0; k < kForward; ++k) total += band.weight[k][b];
            for (int k = 0; k < kForward; ++k) total += band.weight[k][b - offset[k]];
            band.total[b] = total;
        }
    for (int it = 0; it < iterations; ++it) {
        float* to = band.to.data();
        const float* from = band.from.data();
        for (int r = 0; r < rows; ++r) {
            const size_t row = at(0, r);
            relaxRow(w, row, offset, band.weight[0].data(), band.weight[1].data(), band.weight[2].data(),
                     band.weight[3].data(), band.shift[0].data(), band.shift[1].data(), band.shift[2].data(),
                     band.shift[3].data(), band.held.data(), band.total.data(), from, to);
        }
        for (const size_t b : band.fixed) to[b] = from[b];  // apart, so the loop above vectorises
        band.from.swap(band.to);
    }
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) out[static_cast<size_t>(y) * w + x] = band.from[at(x, y - ys)];
}

}  // namespace

int relaxationIterations(int level) { return level == 0 ? 4 : 8; }

void relaxOffsets(const DatabaseLevel& db, const LevelRegion& region, double spacing_m, int iterations,
                  const RelaxationInputs& inputs, PixelState* state) {
    const int h = region.height;
    const size_t pixels = region.pixels();
    if (iterations <= 0 || pixels == 0) return;
    // Frozen pixels take their recorded relaxed state; they, constrained pixels and those carrying a
    // drainage ceiling keep their V.
    std::vector<uint8_t> fixed;
    holdFrozenAndConstrained(db, inputs.coherence, inputs.relaxed, inputs.blend, pixels, state, fixed);
    for (size_t i = 0; i < pixels; ++i)
        if (std::isfinite(state[i].ceiling)) fixed[i] = 1;
    const float gentle = static_cast<float>(std::tan(kRelaxFlatSlopeDegrees * M_PI / 180.0) * spacing_m);
    std::vector<float> relaxed(pixels);
    const int bands = (h + kBandRows - 1) / kBandRows;
    const int workers = std::min(hardwareThreads(), bands);
    runOnWorkers(workers, [&](int worker) {
        BandScratch scratch;
        for (int band = worker; band < bands; band += workers) {
            const int y0 = band * kBandRows, y1 = std::min(h, y0 + kBandRows);
            relaxBand(db, region, gentle, iterations, fixed, state, y0, y1, std::max(0, y0 - iterations),
                      std::min(h, y1 + iterations), scratch, relaxed.data());
        }
    });
    for (size_t i = 0; i < pixels; ++i) state[i].v = relaxed[i];
}

}  // namespace terrasynth::synth
