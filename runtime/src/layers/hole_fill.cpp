// Hole filling by image quilting (Efros & Freeman 2001) in spiral order (Bradbury et al. 2014, s4.4).
//
// Blocks of patch_px cover the hole on a grid with overlap_px overlap and are synthesised ring by
// ring from the outside in, so every block is constrained by terrain (original or already
// synthesised) on its outer sides and the matching error is spread over the region rather than
// accumulating against the last boundary a scan-line order reaches. Each block is the best of
// `candidates` random source blocks from outside the hole (with a height offset fitted to the known
// overlap), joined along minimum-error boundary cuts on every side that overlaps known terrain.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "layers/pyramid.h"
#include "layers/random.h"
#include "terrasynth/layers_tools.h"
#include "terrasynth/limits.h"

namespace terrasynth {
namespace {

struct Grid {
    int w, h;
    size_t at(int x, int y) const { return static_cast<size_t>(y) * w + x; }
};

// Integral image of a 0/1 mask for O(1) "does this block touch the hole" queries.
struct Integral {
    int w, h;
    std::vector<int> s;
    explicit Integral(const std::vector<uint8_t>& m, int w_, int h_) : w(w_), h(h_), s(static_cast<size_t>(w_ + 1) * (h_ + 1), 0) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                s[(y + 1) * (w + 1) + x + 1] = m[static_cast<size_t>(y) * w + x] + s[y * (w + 1) + x + 1] +
                                               s[(y + 1) * (w + 1) + x] - s[y * (w + 1) + x];
    }
    int sum(int x0, int y0, int x1, int y1) const {
        return s[y1 * (w + 1) + x1] - s[y0 * (w + 1) + x1] - s[y1 * (w + 1) + x0] + s[y0 * (w + 1) + x0];
    }
};

// Blocks of the covering grid, ordered as a spiral from the outer ring inward.
std::vector<std::pair<int, int>> spiralOrder(int nx, int ny) {
    std::vector<std::pair<int, int>> order;
    int left = 0, top = 0, right = nx - 1, bottom = ny - 1;
    while (left <= right && top <= bottom) {
        for (int i = left; i <= right; ++i) order.push_back({i, top});
        for (int j = top + 1; j <= bottom; ++j) order.push_back({right, j});
        if (top < bottom)
            for (int i = right - 1; i >= left; --i) order.push_back({i, bottom});
        if (left < right)
            for (int j = bottom - 1; j > top; --j) order.push_back({left, j});
        ++left, ++top, --right, --bottom;
    }
    return order;
}

// Minimum-error path through an `rows` x `cols` error band, one column per row (DP with 8-connected
// steps). Returns the cut column per row.
std::vector<int> minCut(const std::vector<double>& e, int rows, int cols) {
    std::vector<double> acc(e);
    for (int r = 1; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            double best = acc[(r - 1) * cols + c];
            if (c > 0) best = std::min(best, acc[(r - 1) * cols + c - 1]);
            if (c + 1 < cols) best = std::min(best, acc[(r - 1) * cols + c + 1]);
            acc[r * cols + c] += best;
        }
    std::vector<int> path(rows);
    int c = static_cast<int>(std::min_element(acc.begin() + (rows - 1) * cols, acc.begin() + rows * cols) -
                             (acc.begin() + (rows - 1) * cols));
    path[rows - 1] = c;
    for (int r = rows - 2; r >= 0; --r) {
        int best = c;
        for (int d = -1; d <= 1; ++d) {
            const int cc = c + d;
            if (cc >= 0 && cc < cols && acc[r * cols + cc] < acc[r * cols + best]) best = cc;
        }
        c = best;
        path[r] = c;
    }
    return path;
}

Heightfield blurred(const Heightfield& f, int levels) {
    layers::Pyramid g = layers::buildGaussian(layers::toPlane(f), levels);
    layers::Plane cur = g.levels.back();
    for (int i = levels - 1; i >= 0; --i) {
        layers::Plane next;
        layers::expand(cur, g.levels[i].width, g.levels[i].height, next);
        cur = std::move(next);
    }
    return layers::toField(std::move(cur), f);
}

Status validateHoleFill(const HoleFillParams& p) {
    if (!(p.hole.width >= 1 && p.hole.height >= 1)) return Status::error("hole: width and height must be >= 1");
    if (p.patch_px < 8 || p.patch_px > 128) return Status::error("patch_px: must be in 8..128");
    if (p.overlap_px < 2 || p.overlap_px > p.patch_px / 2) return Status::error("overlap_px: must be in 2..patch_px/2");
    if (p.candidates < 16 || p.candidates > 20000) return Status::error("candidates: must be in 16..20000");
    if (!(p.guide_weight >= 0.0 && p.guide_weight < 1.0)) return Status::error("guide_weight: must be in [0, 1)");
    if (p.choices.empty()) return Status::error("choices: needs at least one pick");
    if (p.choices.size() > static_cast<size_t>(limits::kMaxHoleFillPicks))
        return Status::error("choices: " + std::to_string(p.choices.size()) + " picks, at most " +
                             std::to_string(limits::kMaxHoleFillPicks) + " (each is a generation of three quilts)");
    for (int c : p.choices)
        if (c < 0 || c > 2) return Status::error("choices: each pick must be 0, 1 or 2");
    return Status::ok();
}

// Smooth interpolation of scattered values (weight 1 where known, 0 elsewhere) by pull-push over a
// Gaussian pyramid (Gortler et al. 1996): coarse levels fill the gaps, fine levels keep known values.
std::vector<float> pullPush(const std::vector<float>& values, const std::vector<float>& weights, int w, int h) {
    std::vector<layers::Plane> v(1, layers::Plane(w, h)), wt(1, layers::Plane(w, h));
    for (size_t i = 0; i < values.size(); ++i) {
        v[0].samples[i] = values[i] * weights[i];
        wt[0].samples[i] = weights[i];
    }
    while (v.back().width > 1 || v.back().height > 1) {
        layers::Plane vw, ww;
        layers::reduce(v.back(), vw, layers::Kernel::Binomial);
        layers::reduce(wt.back(), ww, layers::Kernel::Binomial);
        for (size_t i = 0; i < vw.samples.size(); ++i) {
            // v holds weighted sums; renormalise so each level stores value*min(1, coverage).
            const float cover = std::min(1.0f, 4.0f * ww.samples[i]);
            const float mean = ww.samples[i] > 0 ? vw.samples[i] / ww.samples[i] : 0.0f;
            vw.samples[i] = mean * cover;
            ww.samples[i] = cover;
        }
        v.push_back(std::move(vw));
        wt.push_back(std::move(ww));
    }
    layers::Plane filled(1, 1);
    filled.samples[0] = wt.back().samples[0] > 0 ? v.back().samples[0] / wt.back().samples[0] : 0.0f;
    for (int l = static_cast<int>(v.size()) - 2; l >= 0; --l) {
        layers::Plane up;
        layers::expand(filled, v[l].width, v[l].height, up);
        for (size_t i = 0; i < up.samples.size(); ++i) {
            const float c = wt[l].samples[i];
            const float mean = c > 0 ? v[l].samples[i] / c : 0.0f;
            up.samples[i] = c * mean + (1.0f - c) * up.samples[i];
        }
        filled = std::move(up);
    }
    return filled.samples;
}

// The quilted blocks continue the terrain only up to an offset: on the rim just outside the hole the
// terrain differs from what the blocks would have put there. That mismatch, interpolated smoothly
// over the hole and added, removes the step at the hole boundary while keeping the quilted detail
// (a membrane correction in the spirit of the gradient-domain blending of s3.2).
void removeRimStep(const Heightfield& terrain, const std::vector<uint8_t>& hole, const std::vector<float>& proposal,
                   Heightfield& out) {
    const int w = terrain.width, h = terrain.height;
    int x0 = w, y0 = h, x1 = 0, y1 = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (hole[static_cast<size_t>(y) * w + x])
                x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + 1), y1 = std::max(y1, y + 1);
    const int m = 2;
    x0 = std::max(0, x0 - m), y0 = std::max(0, y0 - m), x1 = std::min(w, x1 + m), y1 = std::min(h, y1 + m);
    const int bw = x1 - x0, bh = y1 - y0;
    std::vector<float> d(static_cast<size_t>(bw) * bh, 0.0f), wt(d.size(), 0.0f);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const size_t k = static_cast<size_t>(y) * w + x;
            if (hole[k]) continue;
            bool rim = false;
            for (auto [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
                const int nx = x + dx, ny = y + dy;
                if (nx >= 0 && ny >= 0 && nx < w && ny < h && hole[static_cast<size_t>(ny) * w + nx]) rim = true;
            }
            if (!rim) continue;
            const size_t b = static_cast<size_t>(y - y0) * bw + (x - x0);
            // Rim pixels no block reached constrain the correction to zero mismatch.
            d[b] = std::isnan(proposal[k]) ? 0.0f : terrain.heights[k] - proposal[k];
            wt[b] = 1.0f;
        }
    std::vector<float> corr = pullPush(d, wt, bw, bh);
    // Pull-push gives the smooth bulk; a few over-relaxed Gauss-Seidel sweeps of Laplace's equation
    // with the rim values fixed make it the membrane that meets every rim pixel exactly.
    for (int it = 0; it < 150; ++it)
        for (int y = 1; y + 1 < bh; ++y)
            for (int x = 1; x + 1 < bw; ++x) {
                const size_t b = static_cast<size_t>(y) * bw + x;
                if (!hole[static_cast<size_t>(y + y0) * w + (x + x0)]) continue;
                const float avg = 0.25f * (corr[b - 1] + corr[b + 1] + corr[b - bw] + corr[b + bw]);
                corr[b] += 1.8f * (avg - corr[b]);
            }
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const size_t k = static_cast<size_t>(y) * w + x;
            if (hole[k]) out.heights[k] += corr[static_cast<size_t>(y - y0) * bw + (x - x0)];
        }
}

// One quilting run.
Heightfield quilt(const Heightfield& terrain, const std::vector<uint8_t>& hole, const std::vector<std::pair<int, int>>& sources, const HoleFillParams& p,
                  const Heightfield* guide, uint64_t seed, int bx0, int by0, int nbx, int nby) {
    const Grid g{terrain.width, terrain.height};
    const int P = p.patch_px, O = p.overlap_px, S = P - O;
    Heightfield out = terrain;
    std::vector<uint8_t> known(hole.size());
    std::vector<float> rim_proposal(hole.size(), std::numeric_limits<float>::quiet_NaN());
    for (size_t i = 0; i < hole.size(); ++i) known[i] = hole[i] ? 0 : 1;
    layers::Rng rng(seed);
    const double alpha = guide ? p.guide_weight : 0.0;
    std::vector<double> err(static_cast<size_t>(P) * P);
    std::vector<uint8_t> keep_old(static_cast<size_t>(P) * P);
    struct Scored {
        double cost, offset;
        int sx, sy;
    };
    std::vector<Scored> scored;
    for (auto [i, j] : spiralOrder(nbx, nby)) {
        const int bx = bx0 + i * S, by = by0 + j * S;
        const int x0 = std::max(0, bx), y0 = std::max(0, by);
        const int x1 = std::min(g.w, bx + P), y1 = std::min(g.h, by + P);
        if (x0 >= x1 || y0 >= y1) continue;
        bool any_unknown = false;
        for (int y = y0; y < y1 && !any_unknown; ++y)
            for (int x = x0; x < x1; ++x)
                if (!known[g.at(x, y)]) {
                    any_unknown = true;
                    break;
                }
        if (!any_unknown) continue;
        // Score random source blocks on the known overlap (after the best height offset) and the guide.
        scored.clear();
        for (int c = 0; c < p.candidates; ++c) {
            const auto [sx, sy] = sources[rng.below(static_cast<int>(sources.size()))];
            double sum_d = 0.0, sum_d2 = 0.0, guide_cost = 0.0;
            int n_known = 0;
            for (int y = y0; y < y1; ++y) {
                const float* src = &terrain.heights[g.at(sx + x0 - bx, sy + y - by)];
                for (int x = x0; x < x1; ++x) {
                    const size_t k = g.at(x, y);
                    if (known[k]) {
                        const double d = out.heights[k] - src[x - x0];
                        sum_d += d;
                        sum_d2 += d * d;
                        ++n_known;
                    }
                }
            }
            const double offset = n_known ? sum_d / n_known : 0.0;
            const double overlap_cost = n_known ? sum_d2 / n_known - offset * offset : 0.0;
            if (alpha > 0.0) {
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) {
                        const double d = terrain.heights[g.at(sx + x - bx, sy + y - by)] + offset - guide->heights[g.at(x, y)];
                        guide_cost += d * d;
                    }
                guide_cost /= (x1 - x0) * (y1 - y0);
            }
            scored.push_back({(1.0 - alpha) * overlap_cost + alpha * guide_cost, offset, sx, sy});
        }
        // Efros & Freeman pick at random among blocks within 10% of the best, for variety.
        double best = std::numeric_limits<double>::max();
        for (const Scored& s : scored) best = std::min(best, s.cost);
        std::vector<const Scored*> near;
        for (const Scored& s : scored)
            if (s.cost <= best * 1.1 + 1e-9) near.push_back(&s);
        const Scored& pick = *near[rng.below(static_cast<int>(near.size()))];
        // Error surface over the block, then a minimum-error cut along every side with known overlap.
        const int bw = x1 - x0, bh = y1 - y0;
        auto newValue = [&](int x, int y) {
            return terrain.heights[g.at(pick.sx + x - bx, pick.sy + y - by)] + pick.offset;
        };
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const size_t k = g.at(x, y);
                const double d = known[k] ? newValue(x, y) - out.heights[k] : 0.0;
                err[(y - y0) * bw + (x - x0)] = d * d;
            }
        std::fill(keep_old.begin(), keep_old.end(), 0);
        const int ob = std::min(O, std::min(bw, bh));
        for (int side = 0; side < 4; ++side) {
            // Map the side's band to (row along the side, column into the block).
            auto pos = [&](int r, int c, int& x, int& y) {
                switch (side) {
                    case 0: x = c, y = r; break;               // left
                    case 1: x = bw - 1 - c, y = r; break;      // right
                    case 2: x = r, y = c; break;               // top
                    default: x = r, y = bh - 1 - c; break;     // bottom
                }
            };
            const int rows = side < 2 ? bh : bw;
            int known_outer = 0;
            std::vector<double> band(static_cast<size_t>(rows) * ob);
            for (int r = 0; r < rows; ++r)
                for (int c = 0; c < ob; ++c) {
                    int x, y;
                    pos(r, c, x, y);
                    band[r * ob + c] = err[y * bw + x];
                    if (c == 0) known_outer += known[g.at(x0 + x, y0 + y)];
                }
            // Only sides whose outer edge mostly borders known terrain get a cut.
            if (2 * known_outer < rows) continue;
            const std::vector<int> cut = minCut(band, rows, ob);
            for (int r = 0; r < rows; ++r)
                for (int c = 0; c < cut[r]; ++c) {
                    int x, y;
                    pos(r, c, x, y);
                    keep_old[y * bw + x] = 1;
                }
        }
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const size_t k = g.at(x, y);
                if (!hole[k] || (known[k] && keep_old[(y - y0) * bw + (x - x0)])) continue;
                out.heights[k] = static_cast<float>(newValue(x, y));
                known[k] = 1;
                // What this block would continue the terrain with just outside the hole: the rim
                // mismatch removed at the end.
                for (auto [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
                    const int qx = x + dx, qy = y + dy;
                    const int sx = pick.sx + qx - bx, sy = pick.sy + qy - by;
                    if (qx < 0 || qy < 0 || qx >= g.w || qy >= g.h || hole[g.at(qx, qy)]) continue;
                    if (sx < 0 || sy < 0 || sx >= g.w || sy >= g.h) continue;
                    rim_proposal[g.at(qx, qy)] = static_cast<float>(terrain.heights[g.at(sx, sy)] + pick.offset);
                }
            }
    }
    removeRimStep(terrain, hole, rim_proposal, out);
    return out;
}

}  // namespace

Result<std::vector<Heightfield>> holeFillVariants(const Heightfield& terrain, const HoleFillParams& p, int generation,
                                                  const Heightfield* guide, int count) {
    if (Status s = validateHoleFill(p); !s) return s;
    TERRASYNTH_REQUIRE(count >= 1, "count must be positive");
    TERRASYNTH_REQUIRE(!guide || (guide->width == terrain.width && guide->height == terrain.height),
                       "guide must match the terrain");
    const int w = terrain.width, h = terrain.height;
    const std::vector<uint8_t> hole = holeMask(p, w, h);
    int hx0 = w, hy0 = h, hx1 = -1, hy1 = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (hole[static_cast<size_t>(y) * w + x]) {
                hx0 = std::min(hx0, x), hx1 = std::max(hx1, x);
                hy0 = std::min(hy0, y), hy1 = std::max(hy1, y);
            }
    if (hx1 < 0) return Status::error("hole: covers no pixel of the grid");
    // Pixels the blocks may rewrite: the hole and a ring of overlap_px around it.
    Region grown = p.hole;
    grown.x -= p.overlap_px, grown.y -= p.overlap_px;
    grown.width += 2 * p.overlap_px, grown.height += 2 * p.overlap_px;
    const std::vector<float> grown_cover = regionMask(grown, 0.0, w, h);
    std::vector<uint8_t> editable(grown_cover.size());
    for (size_t i = 0; i < editable.size(); ++i) editable[i] = grown_cover[i] >= 0.5f || hole[i];
    const Integral forbidden(editable, w, h);
    const int P = p.patch_px;
    std::vector<std::pair<int, int>> sources;
    const int stride = std::max(1, P / 8);
    for (int y = 0; y + P <= h; y += stride)
        for (int x = 0; x + P <= w; x += stride)
            if (forbidden.sum(x, y, x + P, y + P) == 0) sources.push_back({x, y});
    if (sources.empty())
        return Status::error("hole: no " + std::to_string(P) + "x" + std::to_string(P) +
                             " source block fits outside the hole; make patch_px or the hole smaller");
    // Block grid covering the hole with overlap_px of known terrain on its outer sides.
    const int S = P - p.overlap_px;
    const int bx0 = hx0 - p.overlap_px, by0 = hy0 - p.overlap_px;
    const int nbx = std::max(1, (hx1 + 1 + p.overlap_px - bx0 - p.overlap_px + S - 1) / S);
    const int nby = std::max(1, (hy1 + 1 + p.overlap_px - by0 - p.overlap_px + S - 1) / S);
    Heightfield guide_low;
    if (guide) guide_low = blurred(*guide, std::max(1, static_cast<int>(std::log2(P / 2))));
    std::vector<Heightfield> out;
    for (int k = 0; k < count; ++k)
        out.push_back(quilt(terrain, hole, sources, p, guide ? &guide_low : nullptr,
                            layers::hash3(p.seed, generation, k), bx0, by0, nbx, nby));
    return out;
}

uint64_t holeFillCost(const HoleFillParams& p, int width, int height, int generations) {
    const auto clipped = [](double at, double size, int grid) {
        const double lo = std::max(0.0, std::floor(at)), hi = std::min(double(grid), std::ceil(at + size));
        return hi > lo ? static_cast<uint64_t>(hi - lo) : uint64_t(0);
    };
    const uint64_t step = static_cast<uint64_t>(std::max(1, p.patch_px - p.overlap_px));
    const uint64_t bx = (clipped(p.hole.x, p.hole.width, width) + p.overlap_px + step - 1) / step;
    const uint64_t by = (clipped(p.hole.y, p.hole.height, height) + p.overlap_px + step - 1) / step;
    const uint64_t per_quilt = bx * by * static_cast<uint64_t>(p.candidates) * p.patch_px * p.patch_px;
    const uint64_t grid = static_cast<uint64_t>(width) * height;
    // Generation 0 scores the overlap only; each later one also the guide.
    const uint64_t g = static_cast<uint64_t>(std::max(0, generations));
    return 3 * (per_quilt * (g > 0 ? 2 * g - 1 : 0) + grid * g);
}

Status checkHoleFillCost(const HoleFillParams& p, int width, int height, int generations) {
    const uint64_t cost = holeFillCost(p, width, height, generations);
    if (cost <= limits::kMaxHoleFillCost) return Status::ok();
    return Status::error("choices: " + std::to_string(generations) + " generations of three quilts would visit " +
                         std::to_string(cost) + " pixels, at most " + std::to_string(limits::kMaxHoleFillCost) +
                         " (fewer picks or candidates, or a smaller hole)");
}

Result<Heightfield> holeFill(const Heightfield& terrain, const HoleFillParams& p) {
    if (Status s = validateHoleFill(p); !s) return s;
    if (Status s = checkHoleFillCost(p, terrain.width, terrain.height, static_cast<int>(p.choices.size())); !s) return s;
    Heightfield chosen;
    for (size_t g = 0; g < p.choices.size(); ++g) {
        auto variants = holeFillVariants(terrain, p, static_cast<int>(g), g ? &chosen : nullptr);
        if (!variants) return variants.status();
        chosen = std::move((*variants)[p.choices[g]]);
    }
    return chosen;
}

}  // namespace terrasynth
