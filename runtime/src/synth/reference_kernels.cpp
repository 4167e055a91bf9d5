// Reference implementation of kernels/synthesis.cl. Keep the two in lock-step: same operations in
// the same order, float only (this file is compiled without FP contraction).
#include "synth/reference_kernels.h"

#include <algorithm>
#include <cmath>

#include "core/hash.h"
#include "synth/initial_patches.h"

namespace terrasynth::synth {
using core::hash3;
using core::hashSigned;
using core::levelSalt;
namespace {

struct Vec4 {
    float x, y, z, w;
};

Vec4 fetchAppearance(const DatabaseLevel& db, int index) {
    const uint16_t* a = &db.appearance[static_cast<size_t>(index) * 4];
    return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2]), static_cast<float>(a[3])};
}

float lerp(float a, float b, float t) { return a + (b - a) * t; }

// A at a real-valued atlas coordinate, in quantised units (s4: real coordinates and bilinear
// sampling avoid snapping). Corrected coordinates are whole pixels, so one tap usually suffices.
Vec4 appearanceBilinearQ(const DatabaseLevel& db, float sx, float sy) {
    const float fx = std::floor(sx), fy = std::floor(sy);
    const float tx = sx - fx, ty = sy - fy;
    const int i = static_cast<int>(fy) * db.width + static_cast<int>(fx);
    const Vec4 a00 = fetchAppearance(db, i);
    if (tx == 0.0f && ty == 0.0f) return a00;
    const Vec4 a10 = fetchAppearance(db, i + 1);
    const Vec4 a01 = fetchAppearance(db, i + db.width), a11 = fetchAppearance(db, i + db.width + 1);
    const Vec4 top{lerp(a00.x, a10.x, tx), lerp(a00.y, a10.y, tx), lerp(a00.z, a10.z, tx), lerp(a00.w, a10.w, tx)};
    const Vec4 bot{lerp(a01.x, a11.x, tx), lerp(a01.y, a11.y, tx), lerp(a01.z, a11.z, tx), lerp(a01.w, a11.w, tx)};
    return {lerp(top.x, bot.x, ty), lerp(top.y, bot.y, ty), lerp(top.z, bot.z, ty), lerp(top.w, bot.w, ty)};
}

const PixelState& stateAt(const std::vector<PixelState>& state, const LevelRegion& r, int lx, int ly) {
    lx = std::clamp(lx, 0, r.width - 1);
    ly = std::clamp(ly, 0, r.height - 1);
    return state[static_cast<size_t>(ly) * r.width + lx];
}

// g(u, v) of eq. 5 in quantised units, with u + v = the neighbour read and v = offset.
Vec4 neighbourAppearanceQ(const DatabaseLevel& db, const PixelState& s, float vx, float vy, float inv_scale0) {
    Vec4 a = appearanceBilinearQ(db, s.x - vx, s.y - vy);
    a.x = a.x + s.v * inv_scale0;
    return a;
}

}  // namespace

float heightBilinear(const DatabaseLevel& db, float sx, float sy) {
    const float fx = std::floor(sx), fy = std::floor(sy);
    const float tx = sx - fx, ty = sy - fy;
    const size_t i = static_cast<size_t>(fy) * db.width + static_cast<size_t>(fx);
    const float top = lerp(db.height_m[i], db.height_m[i + 1], tx);
    const float bot = lerp(db.height_m[i + db.width], db.height_m[i + db.width + 1], tx);
    return lerp(top, bot, ty);
}

uint32_t identityCandidate(const DatabaseLevel& db, uint32_t c) {
    if (db.exemplar[c] == kNoExemplar) return c;
    const AtlasRect& r = db.rects[db.exemplar[c]];
    const int x = static_cast<int>(c % static_cast<uint32_t>(db.width)), y = static_cast<int>(c / static_cast<uint32_t>(db.width));
    const bool interior = x >= r.x + kInteriorMargin && x <= r.x + r.width - 1 - kInteriorMargin &&
                          y >= r.y + kInteriorMargin && y <= r.y + r.height - 1 - kInteriorMargin;
    return interior && db.type[c] != kNoType ? c : kNoIdentityCandidate;  // kNoType: a void or its margin
}

void takePrevious(const DatabaseLevel& db, const PassHistory& previous, size_t pixel, PixelState& out) {
    const uint32_t q = previous.index[pixel];
    out.x = static_cast<float>(q % static_cast<uint32_t>(db.width));
    out.y = static_cast<float>(q / static_cast<uint32_t>(db.width));
    out.v = previous.v[pixel];
}

void holdFrozenAndConstrained(const DatabaseLevel& db, const std::vector<uint8_t>* coherence, const PassHistory* recorded,
                              const std::vector<float>* blend, size_t pixels, PixelState* state,
                              std::vector<uint8_t>& fixed) {
    fixed.assign(pixels, 0);
    const bool frozen = coherence && coherence->size() == pixels;
    const bool have_recorded = recorded && recorded->index.size() == pixels;
    const bool constrained = blend && blend->size() == 4 * pixels;
    if (!frozen && !constrained) return;  // a synthesis with neither freezes nor constraints
    for (size_t i = 0; i < pixels; ++i) {
        if (frozen && (*coherence)[i] == static_cast<uint8_t>(Coherence::Frozen)) {
            fixed[i] = 1;
            if (have_recorded && recorded->index[i] != kNoPrevious) takePrevious(db, *recorded, i, state[i]);
        }
        if (constrained && (*blend)[4 * i] > 0.0f) fixed[i] = 1;
    }
}

namespace {

int wrapInto(int v, int n) {
    const int m = v % n;
    return m < 0 ? m + n : m;
}

}  // namespace

void referencePatches(const DatabaseLevel& db, const ShareLayout& layout, const LevelRegion& region, uint32_t seed,
                      int level, bool admit_only, std::vector<PixelState>& state) {
    if (!admit_only) state.assign(region.pixels(), PixelState{0.0f, 0.0f, 0.0f, INFINITY});
    TERRASYNTH_REQUIRE(state.size() == region.pixels() && layout.exemplar.size() == region.pixels(),
                       "referencePatches: state or layout does not match the region");
    const uint32_t salt = levelSalt(seed, level, 0);
    const int cell = kInitialPatchSize;
    for (int ly = 0; ly < region.height; ++ly)
        for (int lx = 0; lx < region.width; ++lx) {
            const int gx = region.x + lx, gy = region.y + ly;
            const int e = layout.exemplar[static_cast<size_t>(ly) * region.width + lx];
            if (admit_only && !layout.entering[e]) continue;
            const int cx = floorDiv(gx, cell), cy = floorDiv(gy, cell);
            int best = 0x7fffffff, site_x = 0, site_y = 0, cell_x = 0, cell_y = 0;
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i) {
                    const int sx = (cx + i) * cell + static_cast<int>(hash3(cx + i, cy + j, salt) % static_cast<uint32_t>(cell));
                    const int sy = (cy + j) * cell + static_cast<int>(hash3(cx + i, cy + j, salt ^ 0x1u) % static_cast<uint32_t>(cell));
                    const int d = (sx - gx) * (sx - gx) + (sy - gy) * (sy - gy);
                    if (d < best) {
                        best = d;
                        site_x = sx, site_y = sy, cell_x = cx + i, cell_y = cy + j;
                    }
                }
            const AtlasRect& r = db.rects[e];
            const int iw = r.width - 2 * kInteriorMargin, ih = r.height - 2 * kInteriorMargin;
            const int ox = static_cast<int>(hash3(cell_x, cell_y, salt ^ 0x3u) % static_cast<uint32_t>(iw));
            const int oy = static_cast<int>(hash3(cell_x, cell_y, salt ^ 0x4u) % static_cast<uint32_t>(ih));
            const int x = r.x + kInteriorMargin + wrapInto(ox + gx - site_x, iw);
            const int y = r.y + kInteriorMargin + wrapInto(oy + gy - site_y, ih);
            PixelState& s = state[static_cast<size_t>(ly) * region.width + lx];
            if (admit_only) {
                // The neighbourhood's mean height (mode 0) stays; see init_level.
                const float gap = appearanceBilinearQ(db, s.x, s.y).x - fetchAppearance(db, y * db.width + x).x;
                s.v = s.v + gap * db.appearance_scale[0];
            }
            s.x = static_cast<float>(x);
            s.y = static_cast<float>(y);
        }
}

void referenceUpsample(const DatabaseLevel& parent_db, const DatabaseLevel& child_db, const LevelRegion& parent_region,
                       const std::vector<PixelState>& parent, const LevelRegion& child_region, float jitter,
                       uint32_t seed, int child_level, std::vector<PixelState>& child) {
    child.assign(child_region.pixels(), PixelState{});
    const uint32_t salt_x = levelSalt(seed, child_level, 1), salt_y = levelSalt(seed, child_level, 2);
    const float margin = static_cast<float>(kInteriorMargin);
    for (int ly = 0; ly < child_region.height; ++ly)
        for (int lx = 0; lx < child_region.width; ++lx) {
            const int gx = child_region.x + lx, gy = child_region.y + ly;
            const int px = floorDiv2(gx), py = floorDiv2(gy);
            const PixelState& p = parent[static_cast<size_t>(py - parent_region.y) * parent_region.width + (px - parent_region.x)];
            const int e = parent_db.exemplar[static_cast<size_t>(std::floor(p.y)) * parent_db.width +
                                             static_cast<size_t>(std::floor(p.x))];
            const AtlasRect& pr = parent_db.rects[e];
            const AtlasRect& cr = child_db.rects[e];
            // Parent pixel centre u maps to child coordinate 2u + 0.5; the child at offset o in {0,1}
            // sits at 2u + 0.5 + (o - 0.5) = 2u + o (eq. 1 with pixel centres at integers).
            float cx = 2.0f * (p.x - static_cast<float>(pr.x)) + static_cast<float>(gx - 2 * px);
            float cy = 2.0f * (p.y - static_cast<float>(pr.y)) + static_cast<float>(gy - 2 * py);
            cx = cx + jitter * hashSigned(hash3(gx, gy, salt_x));
            cy = cy + jitter * hashSigned(hash3(gx, gy, salt_y));
            cx = std::fmin(std::fmax(cx, margin), static_cast<float>(cr.width - 1) - margin);
            cy = std::fmin(std::fmax(cy, margin), static_cast<float>(cr.height - 1) - margin);
            PixelState& c = child[static_cast<size_t>(ly) * child_region.width + lx];
            c.x = static_cast<float>(cr.x) + cx;
            c.y = static_cast<float>(cr.y) + cy;
            c.v = p.v;  // eq. 2
            c.ceiling = p.ceiling;  // the drainage ceiling (drainage_breach.h)
        }
}

namespace {

// Eq. 7 for candidate q in quantised units (see the kernel's candidate_cost); median_offset: h is
// the median of the four mode-0 gaps (kMedianOffsetLevels), in the kernel's selects.
float candidateCost(const DatabaseLevel& db, const Vec4* ns, int q, const float* weight, float kappa, bool median_offset,
                    float* h_out) {
    static const int kDiagonals[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    Vec4 d[4];
    for (int k = 0; k < 4; ++k) {
        const Vec4 a = fetchAppearance(db, q + kDiagonals[k][0] + kDiagonals[k][1] * db.width);
        d[k] = {ns[k].x - a.x, ns[k].y - a.y, ns[k].z - a.z, ns[k].w - a.w};
    }
    const float lo_01 = d[0].x < d[1].x ? d[0].x : d[1].x, hi_01 = d[0].x < d[1].x ? d[1].x : d[0].x;
    const float lo_23 = d[2].x < d[3].x ? d[2].x : d[3].x, hi_23 = d[2].x < d[3].x ? d[3].x : d[2].x;
    const float h = median_offset ? ((lo_01 > lo_23 ? lo_01 : lo_23) + (hi_01 < hi_23 ? hi_01 : hi_23)) * 0.5f
                                  : (d[0].x + d[1].x + d[2].x + d[3].x) * 0.25f;
    float c0 = 0.0f, c1 = 0.0f, c2 = 0.0f, c3 = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const float ex = d[k].x - h;
        c0 = c0 + ex * ex;
        c1 = c1 + d[k].y * d[k].y;
        c2 = c2 + d[k].z * d[k].z;
        c3 = c3 + d[k].w * d[k].w;
    }
    *h_out = h;
    return (weight[0] * c0 + weight[1] * c1 + weight[2] * c2 + weight[3] * c3) * kappa;
}

// phi_d of eq. 8-9.
float phiD(float x, float d, float s, float lambda) {
    const float t = std::fmax(s * d, 1e-3f);
    const float b = -lambda / (3.0f * t * t);
    const float c = b * t * t * t + lambda * t;
    if (x < -t) return lambda * x + c;
    if (x > t) return lambda * x - c;
    return -b * x * x * x;
}

}  // namespace

void referencePreviewLevel(const DatabaseLevel& db, const LevelRegion& region, const std::vector<uint8_t>& coherence,
                           const PassHistory& previous, PixelState* state) {
    const size_t pixels = region.pixels();
    // Atlas coordinates are never negative: truncation is floor (as in the kernels).
    for (size_t i = 0; i < pixels; ++i) {
        state[i].x = static_cast<float>(static_cast<int>(state[i].x + 0.5f));
        state[i].y = static_cast<float>(static_cast<int>(state[i].y + 0.5f));
    }
    // A child sits a quarter of a parent pixel from its own parent's centre towards the parent on
    // its side (west when its global x is even, east when odd), whose V the neighbour on that side
    // holds: V moves a quarter of the way there, when that neighbour continues the child's own
    // exemplar coordinate (inside a patch, where V ramps under a constraint). Across a seam the
    // offsets differ by whatever makes the parents' heights meet, so V stays.
    const std::vector<PixelState> upsampled(state, state + pixels);
    auto shift = [&](size_t i, size_t o, float dx, float dy) {
        const PixelState &a = upsampled[i], &b = upsampled[o];
        const bool continues = b.x == a.x + dx && b.y == a.y + dy;
        return continues ? 0.25f * (b.v - a.v) : 0.0f;
    };
    const bool can_keep = !coherence.empty() && !previous.index.empty();
    for (int y = 0; y < region.height; ++y) {
        const int oy = ((region.y + y) & 1) ? y + 1 : y - 1;
        for (int x = 0; x < region.width; ++x) {
            const size_t i = static_cast<size_t>(y) * region.width + x;
            if (can_keep && static_cast<Coherence>(coherence[i]) != Coherence::Free && previous.index[i] != kNoPrevious) {
                takePrevious(db, previous, i, state[i]);
                continue;
            }
            const int ox = ((region.x + x) & 1) ? x + 1 : x - 1;
            float v = upsampled[i].v;
            if (ox >= 0 && ox < region.width) v += shift(i, static_cast<size_t>(y) * region.width + ox, static_cast<float>(ox - x), 0.0f);
            if (oy >= 0 && oy < region.height) v += shift(i, static_cast<size_t>(oy) * region.width + x, 0.0f, static_cast<float>(oy - y));
            state[i].v = v;
        }
    }
}

void referenceCorrect(const DatabaseLevel& db, const LevelRegion& region, int parity_x, int parity_y, int inset,
                      const CorrectionContext& context, std::vector<PixelState>& state) {
    static const int kDiagonals[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    const float* scale = db.appearance_scale;
    const float inv_scale0 = 1.0f / scale[0];
    const float weight[4] = {scale[0] * scale[0], scale[1] * scale[1], scale[2] * scale[2], scale[3] * scale[3]};
    const constraints::LevelConstraints& constraints = context.constraints;
    const bool median_offset = context.level < kMedianOffsetLevels;
    const int first_x = inset + ((parity_x - region.x - inset) & 1), first_y = inset + ((parity_y - region.y - inset) & 1);
    for (int ly = first_y; ly < region.height - inset; ly += 2) {
        for (int lx = first_x; lx < region.width - inset; lx += 2) {
            // N_S (eq. 6): each diagonal neighbour averaged over three ways of reaching it.
            Vec4 ns[4];
            for (int k = 0; k < 4; ++k) {
                const int dx = kDiagonals[k][0], dy = kDiagonals[k][1];
                const Vec4 g0 = neighbourAppearanceQ(db, stateAt(state, region, lx + dx, ly + dy), 0.0f, 0.0f, inv_scale0);
                const Vec4 g1 = neighbourAppearanceQ(db, stateAt(state, region, lx + 2 * dx, ly + dy), static_cast<float>(dx), 0.0f, inv_scale0);
                const Vec4 g2 = neighbourAppearanceQ(db, stateAt(state, region, lx + dx, ly + 2 * dy), 0.0f, static_cast<float>(dy), inv_scale0);
                const float third = 1.0f / 3.0f;
                ns[k] = {(g0.x + g1.x + g2.x) * third, (g0.y + g1.y + g2.y) * third, (g0.z + g1.z + g2.z) * third,
                         (g0.w + g1.w + g2.w) * third};
            }
            const size_t pixel = static_cast<size_t>(ly) * region.width + lx;
            uint32_t target = constraints.target_sets.empty() ? 0u : constraints.target_sets[pixel];
            if (target != 0u && constraints.types_keep_only) {
                // The finest levels keep painted types only where the pixel has one (constraint_fields.h).
                const PixelState& s = state[pixel];
                const size_t own = static_cast<size_t>(std::floor(s.y + 0.5f)) * db.width + static_cast<size_t>(std::floor(s.x + 0.5f));
                const uint32_t type = db.type[own];
                if (type >= 32u || ((target >> type) & 1u) == 0u) target = 0u;
            }
            // The coarsest level holds the share layout (kernel correct, layout_kappa).
            auto layoutKappa = [&](float kappa, int q) {
                return !context.layout.empty() && db.exemplar[q] != context.layout[pixel] ? kappa * kLayoutWeight : kappa;
            };
            float best_cost = INFINITY, best_h = 0.0f;
            int best_q = -1;
            bool keep_v = false;
            if (!context.coherence.empty() && !context.previous.index.empty() && context.previous.index[pixel] != kNoPrevious) {
                // s5.3: the previous result is the first candidate, its cost times W; frozen keeps it.
                const int q = static_cast<int>(context.previous.index[pixel]);
                const auto code = static_cast<Coherence>(context.coherence[pixel]);
                if (code == Coherence::Frozen) {
                    takePrevious(db, context.previous, pixel, state[pixel]);
                    continue;
                }
                // A repainted pixel's previous source competes only when it is of a painted type
                // (s5.2 rejects every other candidate; without this an edit could never repaint).
                if (target == 0u || ((target >> db.type[q]) & 1u) != 0u) {
                    float h;
                    const float kappa = layoutKappa(code == Coherence::Free ? 1.0f : kCoherentWeight, q);
                    best_cost = candidateCost(db, ns, q, weight, kappa, median_offset, &h);
                    best_q = q;
                    best_h = h;
                    keep_v = code != Coherence::Free;  // coherent pixels keep their offset, so it cannot drift
                }
            }
            // Candidates (eq. 3): C_j(S(p + D) - D) for the 3x3 neighbours D and j = 1, 2. (The kernel
            // skips sources already evaluated; with ties keeping the first, the winner is the same.)
            for (int ddy = -1; ddy <= 1; ++ddy) {
                for (int ddx = -1; ddx <= 1; ++ddx) {
                    const PixelState& s = stateAt(state, region, lx + ddx, ly + ddy);
                    const int cx = static_cast<int>(std::floor(s.x - static_cast<float>(ddx) + 0.5f));
                    const int cy = static_cast<int>(std::floor(s.y - static_cast<float>(ddy) + 0.5f));
                    const int c = cy * db.width + cx;
                    // kNoIdentityCandidate reads as -1.
                    const int candidates[2] = {static_cast<int>(identityCandidate(db, static_cast<uint32_t>(c))),
                                               static_cast<int>(db.similar[c])};
                    for (int j = 0; j < 2; ++j) {
                        const int q = candidates[j];
                        if (q < 0) continue;
                        if (target != 0u && ((target >> db.type[q]) & 1u) == 0u) continue;  // s5.2 rejection
                        float h;
                        const float cost = candidateCost(db, ns, q, weight, layoutKappa(j == 0 ? 1.0f : 2.0f, q), median_offset, &h);
                        if (cost < best_cost) {
                            best_cost = cost;
                            best_q = q;
                            best_h = h;
                            keep_v = false;
                        }
                    }
                }
            }
            const int gx = region.x + lx, gy = region.y + ly;
            if (best_q < 0 && !constraints.types_keep_only) {
                // s5.2 seeding: nine random coordinates of each target type.
                for (int t = 0; t < kMaxPaintableTypes; ++t) {
                    if (((target >> t) & 1u) == 0u) continue;
                    const int offset = context.seeds.ranges[2 * t], count = context.seeds.ranges[2 * t + 1];
                    for (int k = 0; k < kSeedsPerType && count > 0; ++k) {
                        const uint32_t pick = hash3(gx * kSeedsPerType + k, gy, context.seed_salt ^ static_cast<uint32_t>(t));
                        const int q = static_cast<int>(context.seeds.seeds[offset + static_cast<int>(pick % static_cast<uint32_t>(count))]);
                        float h;
                        const float cost = candidateCost(db, ns, q, weight, layoutKappa(2.0f, q), median_offset, &h);
                        if (cost < best_cost) {
                            best_cost = cost;
                            best_q = q;
                            best_h = h;
                        }
                    }
                }
            }
            if (best_q < 0) {
                // Every candidate was rejected (a painted type without seed coordinates at this
                // level) or costs too much to compare: the pixel keeps its own coordinate S(p)
                // (interior after upsampling; synthesis.cl does the same).
                const PixelState& s = state[pixel];
                best_q = static_cast<int>(std::floor(s.y + 0.5f)) * db.width + static_cast<int>(std::floor(s.x + 0.5f));
                candidateCost(db, ns, best_q, weight, 1.0f, median_offset, &best_h);
            }
            float v = best_h * scale[0];
            if (keep_v) v = context.previous.v[pixel];
            const uint8_t* level = context.level_ground ? context.level_ground->data() : nullptr;
            if (!keep_v && level && level[best_q]) {
                // Level ground settles as water does (level_ground.h): no higher than its lowest
                // neighbour copied from the same level ground.
                const float own = db.height_m[static_cast<size_t>(best_q)];
                float lowest = INFINITY;
                for (int ddy = -1; ddy <= 1; ++ddy)
                    for (int ddx = -1; ddx <= 1; ++ddx) {
                        if (ddx == 0 && ddy == 0) continue;
                        const PixelState& s = stateAt(state, region, lx + ddx, ly + ddy);
                        const size_t q = static_cast<size_t>(std::floor(s.y + 0.5f)) * db.width + static_cast<size_t>(std::floor(s.x + 0.5f));
                        if (level[q] && std::fabs(db.height_m[q] - own) <= context.level_tolerance)
                            lowest = std::fmin(lowest, db.height_m[q] + s.v);
                    }
                if (lowest < INFINITY) v = std::fmin(v, lowest - own);
            }
            const float ceiling = state[pixel].ceiling;
            // s5.1: the blended target of the constraints reaching this pixel.
            const float* sums =
                constraints.blend.empty() ? nullptr : &constraints.blend[(static_cast<size_t>(ly) * region.width + lx) * 4];
            const bool constrained = sums && sums[0] > 0.0f;
            if (constrained && !keep_v) {
                // h_c = E(q) + V, the candidate's own height (see synthesis.cl).
                const float candidate_height = db.height_m[static_cast<size_t>(best_q)] + v;
                v = v + phiD(sums[1] / sums[0] - candidate_height, sums[2] / sums[0], kPointToleranceSlope, kPointBlendSlope);
            }
            // Nothing below the exemplars' lowest ground (level_ground.h, lowestExemplarHeight) but
            // what constraints ask for and the channels a coarser level carved (the ceiling, next).
            if (!keep_v && !constrained) v = std::fmax(v, context.lowest_height - db.height_m[static_cast<size_t>(best_q)]);
            // Drainage (drainage_breach.h): carved channels stay at or below their carved height; constraints
            // win over channels.
            if (ceiling < INFINITY && !constrained) v = std::fmin(v, ceiling - db.height_m[static_cast<size_t>(best_q)]);
            PixelState& out = state[static_cast<size_t>(ly) * region.width + lx];
            out.x = static_cast<float>(best_q % db.width);
            out.y = static_cast<float>(best_q / db.width);
            out.v = v;
        }
    }
}

void referenceResolve(const DatabaseLevel& db, const LevelRegion& region, const std::vector<PixelState>& state,
                      const LevelRegion& out, float* heights, float* source_x, float* source_y,
                      uint8_t* source_exemplar) {
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const PixelState& s = state[static_cast<size_t>(out.y - region.y + y) * region.width + (out.x - region.x + x)];
            const size_t o = static_cast<size_t>(y) * out.width + x;
            heights[o] = pixelHeight(db, s);
            if (source_x) {
                const int e = db.exemplar[static_cast<size_t>(std::floor(s.y)) * db.width + static_cast<size_t>(std::floor(s.x))];
                source_x[o] = s.x - static_cast<float>(db.rects[e].x);
                source_y[o] = s.y - static_cast<float>(db.rects[e].y);
                source_exemplar[o] = static_cast<uint8_t>(e);
            }
        }
}

}  // namespace terrasynth::synth
