// The similar-neighbourhood table C_2 (Gain et al. 2015 s4, "Best matches are found using
// PatchMatch [BSFG09], executed on the CPU with multiple threads").
//
// The level-0 atlas of all shared exemplars has ~6M pixels, so every PatchMatch candidate is a
// random read from a ~200 MB feature array, and terrain neighbourhood fields are far less coherent
// than photographs' (propagation alone finds poor matches). Hence:
//  - initialisation by a few random-projection trees (leaves of pixels close in all feature
//    dimensions, compared pairwise), plus the coarser level's matches carried down when the
//    builder provides them (it builds the coarsest level first);
//  - a candidate's distance is computed first and its eligibility/separation checked only when it
//    would win, so most candidates cost one memory read, not three;
//  - random-search candidates are generated together and prefetched before any is compared, and
//    their radius is capped (kRandomSearchRadius);
//  - inverse enrichment runs in parallel, combining proposals with an atomic minimum.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "db/db_internal.h"
#include "core/hash.h"

namespace terrasynth::db {
namespace {

constexpr uint32_t kNoMatch = std::numeric_limits<uint32_t>::max();

bool separated(const PatchMatchInput& in, uint32_t p, uint32_t q) {
    if (in.exemplar[p] != in.exemplar[q]) return true;
    const int px = static_cast<int>(p % in.width), py = static_cast<int>(p / in.width);
    const int qx = static_cast<int>(q % in.width), qy = static_cast<int>(q / in.width);
    return std::max(std::abs(px - qx), std::abs(py - qy)) >= kSimilarSeparation;
}

// Squared distance between feature vectors; the fixed-size case lets the compiler unroll and
// vectorise it.
// Four independent partial sums, so the loop vectorises without reassociating floats.
template <int Dims>
inline float distanceOf(const float* a, const float* b, int dims) {
    float sum[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const int count = Dims > 0 ? Dims : dims;
    int k = 0;
    for (; k + 4 <= count; k += 4)
        for (int l = 0; l < 4; ++l) {
            const float d = a[k + l] - b[k + l];
            sum[l] += d * d;
        }
    for (; k < count; ++k) {
        const float d = a[k] - b[k];
        sum[0] += d * d;
    }
    return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

// Seeding by random-projection trees (a randomised kd-forest): each tree splits the exemplar
// pixels at the median of their features along a pseudo-random direction until leaves hold at
// most kLeafSize pixels, and every pair inside a leaf is compared. Pixels sharing a leaf are close
// in all feature dimensions, not just along one projection, so a few trees place most pixels near
// their nearest neighbour; PatchMatch propagation then spreads the good matches. Without a prior
// guess more trees are grown; with one (the coarser level's matches) fewer suffice.
constexpr int kTrees = 6;
constexpr int kTreesWithPrior = 4;
constexpr int kLeafSize = 48;
constexpr int kParallelDepth = 4;  // the tree's top levels are split serially into 2^4 subtrees

struct TreePoint {
    float f[kMatchModes];
    float key;
    uint32_t pixel;
};

class TreeSeeder {
public:
    TreeSeeder(const PatchMatchInput& in, std::vector<uint32_t>& field, std::vector<float>& cost)
        : in_(in), field_(field), cost_(cost) {}

    void grow(const std::vector<uint32_t>& pixels, int tree, int threads) {
        points_.resize(pixels.size());
        for (size_t i = 0; i < pixels.size(); ++i) {
            TreePoint& t = points_[i];
            std::fill(std::begin(t.f), std::end(t.f), 0.0f);
            std::copy_n(in_.features + static_cast<size_t>(pixels[i]) * in_.dims, in_.dims, t.f);
            t.pixel = pixels[i];
        }
        tree_ = tree;
        // Breadth-first serial splits down to kParallelDepth, then whole subtrees in parallel;
        // the subtree boundaries do not depend on the thread count.
        struct Node { size_t lo, hi; uint32_t id; };
        std::vector<Node> nodes = {{0, points_.size(), 1}};
        for (int depth = 0; depth < kParallelDepth; ++depth) {
            std::vector<Node> next;
            for (const Node& n : nodes) {
                if (n.hi - n.lo <= static_cast<size_t>(kLeafSize)) {
                    next.push_back(n);
                    continue;
                }
                const size_t mid = split(n.lo, n.hi, n.id);
                next.push_back({n.lo, mid, 2 * n.id});
                next.push_back({mid, n.hi, 2 * n.id + 1});
            }
            nodes.swap(next);
        }
        parallelRows(static_cast<int>(nodes.size()), threads, [&](int a, int b) {
            for (int i = a; i < b; ++i) descend(nodes[i].lo, nodes[i].hi, nodes[i].id);
        });
    }

private:
    // Reorders [lo, hi) so the lower half along this node's direction comes first; returns the middle.
    size_t split(size_t lo, size_t hi, uint32_t node) {
        float direction[kMatchModes];
        for (int d = 0; d < kMatchModes; ++d)
            direction[d] = core::hashSigned(core::hash3(tree_, static_cast<int>(node) * kMatchModes + d, in_.salt ^ 0x7ee5u));
        for (size_t i = lo; i < hi; ++i) {
            float sum = 0.0f;
            for (int d = 0; d < kMatchModes; ++d) sum += points_[i].f[d] * direction[d];
            points_[i].key = sum;
        }
        const size_t mid = lo + (hi - lo) / 2;
        std::nth_element(points_.begin() + lo, points_.begin() + mid, points_.begin() + hi,
                         [](const TreePoint& a, const TreePoint& b) {
                             return a.key < b.key || (a.key == b.key && a.pixel < b.pixel);
                         });
        return mid;
    }

    void descend(size_t lo, size_t hi, uint32_t node) {
        if (hi - lo <= static_cast<size_t>(kLeafSize)) {
            compareLeaf(lo, hi);
            return;
        }
        const size_t mid = split(lo, hi, node);
        descend(lo, mid, 2 * node);
        descend(mid, hi, 2 * node + 1);
    }

    // Every pair of the leaf, each distance computed once and offered to both ends.
    void compareLeaf(size_t lo, size_t hi) {
        const int count = static_cast<int>(hi - lo);
        int x[kLeafSize], y[kLeafSize];
        uint8_t exemplar[kLeafSize], eligible[kLeafSize];
        float best_cost[kLeafSize];
        uint32_t best[kLeafSize];
        for (int i = 0; i < count; ++i) {
            const uint32_t p = points_[lo + i].pixel;
            x[i] = static_cast<int>(p % in_.width);
            y[i] = static_cast<int>(p / in_.width);
            exemplar[i] = in_.exemplar[p];
            eligible[i] = in_.eligible[p];
            best_cost[i] = cost_[p];
            best[i] = field_[p];
        }
        auto offer = [&](int i, int j, float c) {  // j as a match for i
            const uint32_t q = points_[lo + j].pixel;
            if (c > best_cost[i] || (c == best_cost[i] && q >= best[i]) || !eligible[j]) return;
            if (exemplar[i] == exemplar[j] && std::max(std::abs(x[i] - x[j]), std::abs(y[i] - y[j])) < kSimilarSeparation)
                return;
            best_cost[i] = c;
            best[i] = q;
        };
        for (int i = 0; i < count; ++i)
            for (int j = i + 1; j < count; ++j) {
                const float c = distanceOf<kMatchModes>(points_[lo + i].f, points_[lo + j].f, kMatchModes);
                offer(i, j, c);
                offer(j, i, c);
            }
        for (int i = 0; i < count; ++i) {
            const uint32_t p = points_[lo + i].pixel;
            cost_[p] = best_cost[i];
            field_[p] = best[i];
        }
    }

    const PatchMatchInput& in_;
    std::vector<uint32_t>& field_;
    std::vector<float>& cost_;
    std::vector<TreePoint> points_;
    int tree_ = 0;
};

void seedFromTrees(const PatchMatchInput& in, const std::vector<uint32_t>& pixels, int trees, int threads,
                   std::vector<uint32_t>& field, std::vector<float>& cost) {
    TreeSeeder seeder(in, field, cost);
    for (int t = 0; t < trees; ++t) seeder.grow(pixels, t, threads);
}

std::vector<uint32_t> eligiblePixels(const PatchMatchInput& in) {
    std::vector<uint32_t> list;
    for (uint32_t i = 0; i < static_cast<uint32_t>(in.width * in.height); ++i)
        if (in.eligible[i]) list.push_back(i);
    return list;
}

// One pixel's running best and the candidate test shared by every search step. The distance is
// computed before the (rarely needed) eligibility and separation checks.
template <int Dims>
struct Best {
    const PatchMatchInput& in;
    uint32_t p;
    int px, py;
    const float* fp;
    float cost;
    uint32_t match;

    void consider(uint32_t q, int qx, int qy) {
        const float c = distanceOf<Dims>(fp, in.features + static_cast<size_t>(q) * in.dims, in.dims);
        if (c > cost || (c == cost && q >= match)) return;
        if (!in.eligible[q]) return;
        if (std::max(std::abs(px - qx), std::abs(py - qy)) < kSimilarSeparation && in.exemplar[q] == in.exemplar[p])
            return;
        cost = c;
        match = q;
    }
    void considerAt(int qx, int qy) {
        if (qx < 0 || qy < 0 || qx >= in.width || qy >= in.height) return;
        consider(static_cast<uint32_t>(qy) * in.width + qx, qx, qy);
    }
    void considerIndex(uint32_t q) {
        if (q == kNoMatch) return;
        consider(q, static_cast<int>(q % in.width), static_cast<int>(q / in.width));
    }
};

// Random search looks this far around the current best at most. The trees already offer every
// pixel candidates from anywhere in the atlas; measured on the shipped exemplars and the 128^2
// test, samples farther out than a few pixels never improved a match, and each costs a cache miss.
constexpr int kRandomSearchRadius = 16;

// The Jacobi-across-bands PatchMatch sweeps (see patchMatch).
template <int Dims>
void sweep(const PatchMatchInput& in, int iterations, int threads, std::vector<uint32_t>& field,
           std::vector<float>& cost) {
    const int max_radius = std::min(kRandomSearchRadius, std::max(in.width, in.height));
    constexpr int kBandRows = 16;
    const int bands = (in.height + kBandRows - 1) / kBandRows;
    const size_t n = field.size();
    std::vector<uint32_t> snapshot(n);
    std::vector<uint64_t> proposals(n);
    for (int it = 0; it < iterations; ++it) {
        snapshot = field;
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
                        Best<Dims> best{in, p, x, y, in.features + static_cast<size_t>(p) * in.dims, cost[p], field[p]};
                        auto propagateFrom = [&](int nx, int ny) {
                            if (nx < 0 || ny < 0 || nx >= in.width || ny >= in.height) return;
                            const uint32_t np = static_cast<uint32_t>(ny) * in.width + nx;
                            if (in.exemplar[np] == kNoExemplar) return;
                            const bool in_band = ny >= y_begin && ny < y_end;
                            const uint32_t match = in_band ? field[np] : snapshot[np];
                            best.considerAt(static_cast<int>(match % in.width) - (nx - x),
                                            static_cast<int>(match / in.width) - (ny - y));
                        };
                        propagateFrom(x + step, y);
                        propagateFrom(x, y + step);
                        // Enrichment: what is similar to my match is likely similar to me.
                        const uint32_t m = best.match;
                        const int my = static_cast<int>(m / in.width);
                        const uint32_t mm = my >= y_begin && my < y_end ? field[m] : snapshot[m];
                        best.considerIndex(mm);  // m is an exemplar pixel: matches always are
                        // Random search around the current best with exponentially shrinking
                        // radius; all candidates are fetched before any is compared.
                        const int bx = static_cast<int>(best.match % in.width), by = static_cast<int>(best.match / in.width);
                        uint32_t candidates[32];
                        int count = 0;
                        uint32_t k = 0;
                        for (int r = max_radius; r >= 1; r /= 2, ++k) {
                            const uint32_t h = core::hash3(static_cast<int>(p), static_cast<int>(it * 64 + k), in.salt ^ 0x9e3779b9u);
                            const int qx = bx + static_cast<int>(h % (2 * r + 1)) - r;
                            const int qy = by + static_cast<int>((h >> 16) % (2 * r + 1)) - r;
                            if (qx < 0 || qy < 0 || qx >= in.width || qy >= in.height) continue;
                            const uint32_t q = static_cast<uint32_t>(qy) * in.width + qx;
                            __builtin_prefetch(in.features + static_cast<size_t>(q) * in.dims);
                            candidates[count++] = q;
                        }
                        for (int c = 0; c < count; ++c) best.considerIndex(candidates[c]);
                        cost[p] = best.cost;
                        field[p] = best.match;
                    }
                }
            }
        });
        // Inverse enrichment (symmetry of similarity): if p's match q is closer to p than to its
        // own match, p becomes q's match; among several such p the closest (then lowest index)
        // wins. Proposals are combined with an atomic minimum, so the result does not depend on
        // the order in which threads deliver them.
        const int rows = in.height;
        parallelRows(rows, threads, [&](int y0, int y1) {
            std::fill(proposals.begin() + static_cast<size_t>(y0) * in.width,
                      proposals.begin() + static_cast<size_t>(y1) * in.width, ~uint64_t{0});
        });
        parallelRows(rows, threads, [&](int y0, int y1) {
            for (uint32_t p = static_cast<uint32_t>(y0) * in.width; p < static_cast<uint32_t>(y1) * in.width; ++p) {
                if (!in.eligible[p]) continue;
                const uint32_t q = field[p];
                if (!(cost[p] < cost[q]) || !separated(in, q, p)) continue;
                uint32_t bits;
                std::memcpy(&bits, &cost[p], sizeof bits);  // costs are >= 0: bits order like values
                const uint64_t offer = (static_cast<uint64_t>(bits) << 32) | p;
                uint64_t current = __atomic_load_n(&proposals[q], __ATOMIC_RELAXED);
                while (offer < current &&
                       !__atomic_compare_exchange_n(&proposals[q], &current, offer, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
                }
            }
        });
        parallelRows(rows, threads, [&](int y0, int y1) {
            for (uint32_t q = static_cast<uint32_t>(y0) * in.width; q < static_cast<uint32_t>(y1) * in.width; ++q) {
                const uint64_t offer = proposals[q];
                if (offer == ~uint64_t{0}) continue;
                const uint32_t bits = static_cast<uint32_t>(offer >> 32);
                std::memcpy(&cost[q], &bits, sizeof bits);
                field[q] = static_cast<uint32_t>(offer);
            }
        });
    }
}

}  // namespace

float featureDistance(const PatchMatchInput& in, uint32_t a, uint32_t b) {
    return distanceOf<0>(in.features + static_cast<size_t>(a) * in.dims, in.features + static_cast<size_t>(b) * in.dims,
                         in.dims);
}

std::vector<uint32_t> patchMatch(const PatchMatchInput& in, int iterations, int threads) {
    const size_t n = static_cast<size_t>(in.width) * in.height;
    std::vector<uint32_t> field(n, 0);
    std::vector<float> cost(n, std::numeric_limits<float>::max());
    const std::vector<uint32_t> pool = eligiblePixels(in);
    if (pool.empty()) return field;
    auto randomEligible = [&](uint32_t p, uint32_t round) {
        for (uint32_t attempt = 0;; ++attempt) {
            const uint32_t q = pool[core::hash3(static_cast<int>(p), static_cast<int>(attempt + 64 * round), in.salt) % pool.size()];
            if (separated(in, p, q) || attempt > 32) return q;
        }
    };
    // Initialisation: the prior guess if acceptable (else a random one), then the random-projection
    // trees. Terrain neighbourhoods are small and self-similar, so the nearest-neighbour field is
    // far less coherent than for photographs; the trees give propagation good matches to spread.
    // (Before the trees, 12 sorted 1-D projections with a +-16 window reached a sampled quality of
    // 0.45 of brute force at level 0 of the shipped exemplars; 4 trees after the prior reach 0.89.)
    std::vector<uint32_t> pixels;
    for (uint32_t p = 0; p < static_cast<uint32_t>(n); ++p)
        if (in.exemplar[p] != kNoExemplar) pixels.push_back(p);
    parallelRows(in.height, threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < in.width; ++x) {
                const uint32_t p = static_cast<uint32_t>(y) * in.width + x;
                if (in.exemplar[p] == kNoExemplar) continue;
                const uint32_t prior = in.initial ? in.initial[p] : kNoMatch;
                field[p] = prior < n && in.eligible[prior] && separated(in, p, prior) ? prior : randomEligible(p, 0);
                cost[p] = featureDistance(in, p, field[p]);
            }
    });
    TERRASYNTH_REQUIRE(in.dims >= 1 && in.dims <= kMatchModes, "PatchMatch feature dimensions");
    seedFromTrees(in, pixels, in.initial ? kTreesWithPrior : kTrees, threads, field, cost);
    // Rows are processed in fixed bands of 16 rows: inside a band propagation is sequential (the
    // classic scan-order PatchMatch, alternating direction per iteration); across band borders a
    // pixel reads the previous iteration's snapshot. The band split does not depend on the thread
    // count, so neither does the result.
    if (in.dims == kMatchModes)
        sweep<kMatchModes>(in, iterations, threads, field, cost);
    else
        sweep<0>(in, iterations, threads, field, cost);
    return field;
}

std::vector<uint32_t> upsampleMatches(const DatabaseLevel& coarse, const std::vector<AtlasRect>& fine_rects,
                                      int fine_width, int fine_height) {
    std::vector<uint32_t> guess(static_cast<size_t>(fine_width) * fine_height, kNoMatch);
    if (coarse.similar.size() != coarse.pixelCount()) return guess;
    for (size_t e = 0; e < fine_rects.size() && e < coarse.rects.size(); ++e) {
        const AtlasRect& f = fine_rects[e];
        const AtlasRect& c = coarse.rects[e];
        if (c.width <= 0 || c.height <= 0) continue;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const int cx = std::min(x / 2, c.width - 1), cy = std::min(y / 2, c.height - 1);
                const uint32_t m = coarse.similar[static_cast<size_t>(c.y + cy) * coarse.width + c.x + cx];
                const uint8_t to = coarse.exemplar[m];
                if (to == kNoExemplar || to >= fine_rects.size()) continue;
                const AtlasRect& tc = coarse.rects[to];
                const AtlasRect& tf = fine_rects[to];
                const int u = static_cast<int>(m % coarse.width) - tc.x, v = static_cast<int>(m / coarse.width) - tc.y;
                const int fx = std::clamp(2 * u + (x - 2 * cx), 0, tf.width - 1);
                const int fy = std::clamp(2 * v + (y - 2 * cy), 0, tf.height - 1);
                guess[static_cast<size_t>(f.y + y) * fine_width + f.x + x] =
                    static_cast<uint32_t>(tf.y + fy) * fine_width + static_cast<uint32_t>(tf.x + fx);
            }
    }
    return guess;
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
