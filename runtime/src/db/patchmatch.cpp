// The similar-neighbourhood table C_2 (Gain et al. 2015 s4, "Best matches are found using
// PatchMatch [BSFG09], executed on the CPU with multiple threads").
#include <algorithm>
#include <cmath>
#include <limits>

#include "db/db_internal.h"
#include "synth/hash.h"

namespace terrasynth::db {
namespace {

bool separated(const PatchMatchInput& in, uint32_t p, uint32_t q) {
    if (in.exemplar[p] != in.exemplar[q]) return true;
    const int px = static_cast<int>(p % in.width), py = static_cast<int>(p / in.width);
    const int qx = static_cast<int>(q % in.width), qy = static_cast<int>(q / in.width);
    return std::max(std::abs(px - qx), std::abs(py - qy)) >= kSimilarSeparation;
}

bool acceptable(const PatchMatchInput& in, uint32_t p, int qx, int qy) {
    if (qx < 0 || qy < 0 || qx >= in.width || qy >= in.height) return false;
    const uint32_t q = static_cast<uint32_t>(qy) * in.width + qx;
    return in.eligible[q] && separated(in, p, q);
}

constexpr int kProjections = 12;
constexpr size_t kProjectionWindow = 16;

// Keys of every pixel along kProjections fixed pseudo-random directions of feature space, and the
// eligible pixels sorted by each key.
struct Projections {
    std::vector<float> keys;                  // pixel * kProjections + k
    std::vector<std::vector<uint32_t>> sorted;
};

Projections sortProjections(const PatchMatchInput& in, const std::vector<uint32_t>& pool, int threads) {
    const size_t n = static_cast<size_t>(in.width) * in.height;
    std::vector<float> directions(static_cast<size_t>(kProjections) * in.dims);
    for (int k = 0; k < kProjections; ++k)
        for (int d = 0; d < in.dims; ++d) directions[k * in.dims + d] = synth::hashSigned(synth::hash3(k, d, 0x5eedu));
    Projections out;
    out.keys.resize(n * kProjections);
    parallelRows(in.height, threads, [&](int y0, int y1) {
        for (size_t p = static_cast<size_t>(y0) * in.width; p < static_cast<size_t>(y1) * in.width; ++p) {
            const float* f = in.features + p * in.dims;
            for (int k = 0; k < kProjections; ++k) {
                float sum = 0.0f;
                for (int d = 0; d < in.dims; ++d) sum += f[d] * directions[k * in.dims + d];
                out.keys[p * kProjections + k] = sum;
            }
        }
    });
    out.sorted.resize(kProjections);
    parallelRows(kProjections, threads, [&](int k0, int k1) {
        for (int k = k0; k < k1; ++k) {
            out.sorted[k] = pool;
            std::sort(out.sorted[k].begin(), out.sorted[k].end(), [&](uint32_t a, uint32_t b) {
                const float ka = out.keys[a * kProjections + k], kb = out.keys[b * kProjections + k];
                return ka < kb || (ka == kb && a < b);
            });
        }
    });
    return out;
}

std::vector<uint32_t> eligiblePixels(const PatchMatchInput& in) {
    std::vector<uint32_t> list;
    for (uint32_t i = 0; i < static_cast<uint32_t>(in.width * in.height); ++i)
        if (in.eligible[i]) list.push_back(i);
    return list;
}

}  // namespace

float featureDistance(const PatchMatchInput& in, uint32_t a, uint32_t b) {
    const float* fa = in.features + static_cast<size_t>(a) * in.dims;
    const float* fb = in.features + static_cast<size_t>(b) * in.dims;
    float sum = 0.0f;
    for (int k = 0; k < in.dims; ++k) {
        const float d = fa[k] - fb[k];
        sum += d * d;
    }
    return sum;
}

std::vector<uint32_t> patchMatch(const PatchMatchInput& in, int iterations, int threads) {
    const size_t n = static_cast<size_t>(in.width) * in.height;
    std::vector<uint32_t> field(n, 0);
    std::vector<float> cost(n, std::numeric_limits<float>::max());
    const std::vector<uint32_t> pool = eligiblePixels(in);
    if (pool.empty()) return field;
    auto randomEligible = [&](uint32_t p, uint32_t round) {
        for (uint32_t attempt = 0;; ++attempt) {
            const uint32_t q = pool[synth::hash3(static_cast<int>(p), static_cast<int>(attempt + 64 * round), in.salt) % pool.size()];
            if (separated(in, p, q) || attempt > 32) return q;
        }
    };
    // Initialisation: besides a random guess, the pixels nearest to p along a few fixed random
    // projections of feature space. Terrain neighbourhoods are small and self-similar, so the
    // nearest-neighbour field is far less coherent than for photographs; seeding from sorted
    // projections gives propagation good matches to spread.
    const Projections projections = sortProjections(in, pool, threads);
    parallelRows(in.height, threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < in.width; ++x) {
                const uint32_t p = static_cast<uint32_t>(y) * in.width + x;
                if (in.exemplar[p] == kNoExemplar) continue;
                field[p] = randomEligible(p, 0);
                cost[p] = featureDistance(in, p, field[p]);
                for (int k = 0; k < kProjections; ++k) {
                    const float key = projections.keys[static_cast<size_t>(p) * kProjections + k];
                    const auto& order = projections.sorted[k];
                    size_t lo = 0, hi = order.size();
                    while (lo < hi) {
                        const size_t mid = (lo + hi) / 2;
                        if (projections.keys[static_cast<size_t>(order[mid]) * kProjections + k] < key) lo = mid + 1;
                        else hi = mid;
                    }
                    const size_t begin = lo > kProjectionWindow ? lo - kProjectionWindow : 0;
                    const size_t end = std::min(order.size(), lo + kProjectionWindow);
                    for (size_t j = begin; j < end; ++j) {
                        const uint32_t q = order[j];
                        if (!separated(in, p, q)) continue;
                        const float c = featureDistance(in, p, q);
                        if (c < cost[p] || (c == cost[p] && q < field[p])) {
                            cost[p] = c;
                            field[p] = q;
                        }
                    }
                }
            }
    });
    const int max_radius = std::max(in.width, in.height);
    // Rows are processed in fixed bands of kBandRows: inside a band propagation is sequential (the
    // classic scan-order PatchMatch, alternating direction per iteration); across band borders a
    // pixel reads the previous iteration's snapshot. The band split does not depend on the thread
    // count, so neither does the result.
    constexpr int kBandRows = 16;
    const int bands = (in.height + kBandRows - 1) / kBandRows;
    for (int it = 0; it < iterations; ++it) {
        const std::vector<uint32_t> snapshot = field;
        const bool forward = it % 2 == 0;
        const int step = forward ? -1 : 1;  // neighbours already visited in this scan
        parallelRows(bands, threads, [&](int b0, int b1) {
            for (int b = b0; b < b1; ++b) {
                const int y_begin = b * kBandRows, y_end = std::min(in.height, y_begin + kBandRows);
                for (int row = 0; row < y_end - y_begin; ++row) {
                    const int y = forward ? y_begin + row : y_end - 1 - row;
                    for (int col = 0; col < in.width; ++col) {
                        const int x = forward ? col : in.width - 1 - col;
                        const uint32_t p = static_cast<uint32_t>(y) * in.width + x;
                        if (in.exemplar[p] == kNoExemplar) continue;
                        auto consider = [&](int qx, int qy) {
                            if (!acceptable(in, p, qx, qy)) return;
                            const uint32_t q = static_cast<uint32_t>(qy) * in.width + qx;
                            const float c = featureDistance(in, p, q);
                            if (c < cost[p] || (c == cost[p] && q < field[p])) {
                                cost[p] = c;
                                field[p] = q;
                            }
                        };
                        auto propagateFrom = [&](int nx, int ny) {
                            if (nx < 0 || ny < 0 || nx >= in.width || ny >= in.height) return;
                            const uint32_t np = static_cast<uint32_t>(ny) * in.width + nx;
                            if (in.exemplar[np] == kNoExemplar) return;
                            const bool in_band = ny >= y_begin && ny < y_end;
                            const uint32_t match = in_band ? field[np] : snapshot[np];
                            consider(static_cast<int>(match % in.width) - (nx - x),
                                     static_cast<int>(match / in.width) - (ny - y));
                        };
                        propagateFrom(x + step, y);
                        propagateFrom(x, y + step);
                        // Enrichment: what is similar to my match is likely similar to me.
                        const uint32_t m = field[p];
                        const int my = static_cast<int>(m / in.width);
                        const uint32_t mm = my >= y_begin && my < y_end ? field[m] : snapshot[m];
                        if (in.exemplar[m] != kNoExemplar) consider(static_cast<int>(mm % in.width), static_cast<int>(mm / in.width));
                        // Random search around the current best with exponentially shrinking radius.
                        const int bx = static_cast<int>(field[p] % in.width), by = static_cast<int>(field[p] / in.width);
                        uint32_t k = 0;
                        for (int r = max_radius; r >= 1; r /= 2, ++k) {
                            const uint32_t h = synth::hash3(static_cast<int>(p), static_cast<int>(it * 64 + k), in.salt ^ 0x9e3779b9u);
                            const int rx = static_cast<int>(h % (2 * r + 1)) - r;
                            const int ry = static_cast<int>((h >> 16) % (2 * r + 1)) - r;
                            consider(bx + rx, by + ry);
                        }
                    }
                }
            }
        });
        // Inverse enrichment (symmetry of similarity): if p's match q is closer to p than to its
        // own match, p becomes q's match. Serial, O(pixels), so deterministic.
        for (uint32_t p = 0; p < static_cast<uint32_t>(n); ++p) {
            if (in.exemplar[p] == kNoExemplar || !in.eligible[p]) continue;
            const uint32_t q = field[p];
            if (cost[p] < cost[q] && separated(in, q, p)) {
                cost[q] = cost[p];
                field[q] = p;
            }
        }
    }
    return field;
}

std::vector<uint32_t> bruteForceMatch(const PatchMatchInput& in) {
    const size_t n = static_cast<size_t>(in.width) * in.height;
    std::vector<uint32_t> field(n, 0);
    const std::vector<uint32_t> pool = eligiblePixels(in);
    parallelRows(in.height, 0, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < in.width; ++x) {
                const uint32_t p = static_cast<uint32_t>(y) * in.width + x;
                if (in.exemplar[p] == kNoExemplar) continue;
                float best = std::numeric_limits<float>::max();
                for (uint32_t q : pool) {
                    if (!separated(in, p, q)) continue;
                    const float c = featureDistance(in, p, q);
                    if (c < best) {
                        best = c;
                        field[p] = q;
                    }
                }
            }
    });
    return field;
}

}  // namespace terrasynth::db
