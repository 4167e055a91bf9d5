// Parallel pixel-based terrain synthesis, Gain, Merry & Marais 2015 section 4.
// Plain C++ reference: runtime/src/synth/reference_kernels.cpp (same operations, same order).
// Tunables (-D): none change results; work-group sizes are chosen by the host.
//
// State per synthesis pixel: float4(S.x, S.y, V, spare) with S an atlas coordinate of the level.
// Database per level: appearance (ushort4, dequantised with offset + scale), similar (uint, C_2),
// exemplar (uchar), rects (int4 x, y, w, h per exemplar), heights (float).

#pragma OPENCL FP_CONTRACT OFF

#define INTERIOR_MARGIN 2
// Paper constants (s5), passed by the host as -D so they live in one place (constraints.h).
#ifndef INIT_PATCH_SIZE
#define INIT_PATCH_SIZE 8
#endif
#ifndef LAYOUT_WEIGHT
#define LAYOUT_WEIGHT 1.0f
#endif
#ifndef SEEDS_PER_TYPE
#define SEEDS_PER_TYPE 9
#endif
#define NO_PREVIOUS 0xffffffffu
#define COHERENCE_FROZEN 0
#define COHERENCE_FREE 2
#ifndef COHERENT_WEIGHT
#define COHERENT_WEIGHT 0.25f
#endif
#ifndef TOLERANCE_SLOPE
#define TOLERANCE_SLOPE 0.5f
#endif
#ifndef BLEND_SLOPE
#define BLEND_SLOPE 0.5f
#endif

typedef struct {
    int x, y, width, height;  // region of the global grid held by a state buffer
} Region;

// Atlas coordinates are never negative, so truncation is floor; plain operators instead of the
// floor/clamp builtins keep PoCL's work-item loops free of calls, which it cannot vectorise.
TS_INLINE int floor_nonneg(float v) { return (int)v; }
TS_INLINE int clamp_int(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

TS_INLINE float4 lerp4(float4 a, float4 b, float t) {
    return (float4)(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t, a.w + (b.w - a.w) * t);
}

// A at a real-valued atlas coordinate, in quantised units (s4: real coordinates and bilinear
// sampling avoid snapping). Corrected coordinates are whole pixels, so one tap usually suffices.
TS_INLINE float4 appearance_bilinear_q(global const ushort4* appearance, int width, float sx, float sy) {
    const int ix = floor_nonneg(sx), iy = floor_nonneg(sy);
    const float tx = sx - (float)ix, ty = sy - (float)iy;
    const int i = iy * width + ix;
    const float4 a00 = convert_float4(appearance[i]);
    if (tx == 0.0f && ty == 0.0f) return a00;
    const float4 a10 = convert_float4(appearance[i + 1]);
    const float4 a01 = convert_float4(appearance[i + width]), a11 = convert_float4(appearance[i + width + 1]);
    return lerp4(lerp4(a00, a10, tx), lerp4(a01, a11, tx), ty);
}

TS_INLINE float4 state_at(global const float4* state, Region r, int lx, int ly) {
    lx = clamp_int(lx, 0, r.width - 1);
    ly = clamp_int(ly, 0, r.height - 1);
    return state[ly * r.width + lx];
}

// g(u, v) of eq. 5 in quantised units: appearance at S(u + v) - v, plus V(u + v) on mode 0.
TS_INLINE float4 neighbour_appearance_q(global const ushort4* appearance, int width, float4 s, float vx, float vy,
                              float inv_scale0) {
    float4 a = appearance_bilinear_q(appearance, width, s.x - vx, s.y - vy);
    a.x = a.x + s.z * inv_scale0;
    return a;
}

TS_INLINE int floor_div2(int v) { return v >> 1; }

// Floor division by a positive divisor, for negative global coordinates too.
TS_INLINE int floor_div(int v, int d) { return v >= 0 ? v / d : -((d - 1 - v) / d); }
// v wrapped into [0, n) (negative v too).
TS_INLINE int wrap_into(int v, int n) {
    int m = v % n;
    return m < 0 ? m + n : m;
}

// Coarsest level (issue 16, synth/initial_patches.h): irregular patches of exemplar coordinates.
// Every INIT_PATCH_SIZE^2 cell of the global grid holds one jittered site; a pixel belongs to the
// nearest site of the 3x3 cells around it (Voronoi cells) and copies the exemplar around one random
// interior position of that cell, wrapped around the interior where the cell reaches past it. A
// wrap is a seam, which the correction passes repair from the exemplar; a mirror (used before) is a
// smooth fold that matches its own neighbourhood, so the passes kept it: mirrored bands in the
// output and a flat bias (docs/realism.md). Which exemplar a pixel copies is its share cell's
// (`layout`, per region pixel, from the host's shareLayout: every block of 1024 level-0 pixels
// holds the exemplars in proportion to their area). V = 0, no drainage ceiling.
// init_cells computes each patch cell's site and offset hashes once (31 hashes per pixel when
// init_level did it for every pixel and each of its 3x3 cells); per cell of the grid [first_cx,
// first_cx + grid_w) x [first_cy, ...): cells[i] = (site x, site y, offset hash x, offset hash y).
kernel void init_cells(global int4* cells, int first_cx, int first_cy, int grid_w, int grid_h, uint salt) {
    const int i = get_global_id(0), j = get_global_id(1);
    if (i >= grid_w || j >= grid_h) return;
    const int cell_x = first_cx + i, cell_y = first_cy + j;
    const int sx = cell_x * INIT_PATCH_SIZE + (int)(ts_hash3(cell_x, cell_y, salt) % (uint)INIT_PATCH_SIZE);
    const int sy = cell_y * INIT_PATCH_SIZE + (int)(ts_hash3(cell_x, cell_y, salt ^ 0x1u) % (uint)INIT_PATCH_SIZE);
    cells[j * grid_w + i] = (int4)(sx, sy, as_int(ts_hash3(cell_x, cell_y, salt ^ 0x3u)),
                                   as_int(ts_hash3(cell_x, cell_y, salt ^ 0x4u)));
}

// With admit_only (a finer level where exemplars enter, synth/initial_patches.h) only the pixels
// whose share cell's exemplar is `entering` take a patch coordinate. They keep their ceiling and
// their neighbourhood's mean height (mode 0, appearance_pca.cpp): V takes the mode-0 gap between
// the old and the new coordinate, so the entering exemplar brings its detail onto the coarser
// levels' terrain. With V kept as it was, its absolute heights came too: a 10-30 m exemplar's
// valley floor entered a Himalayan region as a flat pit 3 km deep, with walls no pass removed.
kernel void init_level(global float4* state, Region region, global const int4* cells, int first_cx, int first_cy,
                       int grid_w, global const uchar* layout, global const int4* rects, global const uchar* entering,
                       int admit_only,
                       global const ushort4* appearance, int width, float scale0) {
    const int lx = get_global_id(0), ly = get_global_id(1);
    if (lx >= region.width || ly >= region.height) return;
    const int gx = region.x + lx, gy = region.y + ly;
    const int e = layout[ly * region.width + lx];
    if (admit_only && !entering[e]) return;
    const int cx = floor_div(gx, INIT_PATCH_SIZE) - first_cx, cy = floor_div(gy, INIT_PATCH_SIZE) - first_cy;
    int best = 0x7fffffff, nearest = 0;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const int c = (cy + j) * grid_w + (cx + i);
            const int4 site = cells[c];
            const int d = (site.x - gx) * (site.x - gx) + (site.y - gy) * (site.y - gy);
            if (d < best) {
                best = d;
                nearest = c;
            }
        }
    const int4 r = rects[e], site = cells[nearest];
    const int iw = r.z - 2 * INTERIOR_MARGIN, ih = r.w - 2 * INTERIOR_MARGIN;
    const int ox = (int)(as_uint(site.z) % (uint)iw), oy = (int)(as_uint(site.w) % (uint)ih);
    const int x = r.x + INTERIOR_MARGIN + wrap_into(ox + gx - site.x, iw);
    const int y = r.y + INTERIOR_MARGIN + wrap_into(oy + gy - site.y, ih);
    float v = 0.0f, ceiling = INFINITY;
    if (admit_only) {
        const float4 old = state[ly * region.width + lx];
        const float gap = appearance_bilinear_q(appearance, width, old.x, old.y).x - (float)appearance[y * width + x].x;
        v = old.z + gap * scale0;
        ceiling = old.w;
    }
    state[ly * region.width + lx] = (float4)((float)x, (float)y, v, ceiling);
}

// Eq. 1-2: each parent pixel initialises its 2x2 children with jittered coordinates; they inherit its
// drainage ceiling too (issue 17).
kernel void upsample_jitter(global const float4* parent, Region parent_region, global float4* child, Region child_region,
                     global const uchar* parent_exemplar, int parent_width, global const int4* parent_rects,
                     global const int4* child_rects, float jitter, uint salt_x, uint salt_y) {
    const int lx = get_global_id(0), ly = get_global_id(1);
    if (lx >= child_region.width || ly >= child_region.height) return;
    const int gx = child_region.x + lx, gy = child_region.y + ly;
    const int px = floor_div2(gx), py = floor_div2(gy);
    const float4 p = parent[(py - parent_region.y) * parent_region.width + (px - parent_region.x)];
    const int e = parent_exemplar[floor_nonneg(p.y) * parent_width + floor_nonneg(p.x)];
    const int4 pr = parent_rects[e], cr = child_rects[e];
    float cx = 2.0f * (p.x - (float)pr.x) + (float)(gx - 2 * px);
    float cy = 2.0f * (p.y - (float)pr.y) + (float)(gy - 2 * py);
    if (jitter != 0.0f) {  // unjittered levels: adding 0 * hash would change no bit (cx, cy > 0)
        cx = cx + jitter * ts_hash_signed(ts_hash3(gx, gy, salt_x));
        cy = cy + jitter * ts_hash_signed(ts_hash3(gx, gy, salt_y));
    }
    const float margin = (float)INTERIOR_MARGIN;
    cx = fmin(fmax(cx, margin), (float)(cr.z - 1) - margin);
    cy = fmin(fmax(cy, margin), (float)(cr.w - 1) - margin);
    child[ly * child_region.width + lx] = (float4)((float)cr.x + cx, (float)cr.y + cy, p.z, p.w);
}

// Eq. 3-7 for the pixels of one parity class (one of the 4 subpasses), in place: a pixel of the
// class only reads pixels of other classes (and itself), so there are no races.
// Eq. 7 for candidate q in quantised units: the best offset h moves mode 0 only, so it is the
// mean mode-0 gap; the cost is the scale^2-weighted squared distance times kappa. The upper two
// diagonals are fetched first; their modes 1..3 alone bound the cost from below (the mode-0 term
// is never negative), so a candidate that cannot beat `best` skips the second cache line. The
// winner is the same as with the full evaluation (the reference does not bother).
// With median_offset (the finest levels, synth::kMedianOffsetLevels) h is the median of the four
// mode-0 gaps, the mean of the middle two, in place of their mean: one diagonal across a patch seam
// does not drag the height of a pixel whose other three agree. Plain selects, no sort.
TS_INLINE float candidate_cost(global const ushort4* appearance, int width, const float4* ns, int q, float4 weight,
                               float kappa, float best, int median_offset, float* h_out) {
    const float4 d0 = ns[0] - convert_float4(appearance[q - 1 - width]);
    const float4 d1 = ns[1] - convert_float4(appearance[q + 1 - width]);
    const float bound = (weight.y * (d0.y * d0.y + d1.y * d1.y) + weight.z * (d0.z * d0.z + d1.z * d1.z) +
                         weight.w * (d0.w * d0.w + d1.w * d1.w)) * kappa;
    if (bound >= best) return INFINITY;
    const float4 d2 = ns[2] - convert_float4(appearance[q - 1 + width]);
    const float4 d3 = ns[3] - convert_float4(appearance[q + 1 + width]);
    const float4 d[4] = {d0, d1, d2, d3};
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
    return (weight.x * c0 + weight.y * c1 + weight.z * c2 + weight.w * c3) * kappa;
}

// phi_d of eq. 8-9: small height errors are nudged gently, large ones by lambda; the tolerance
// t = s * d metres grows with the distance d (level-0 pixels) from the constraint site. (With d in
// metres the tolerance at 10 pixels of 90 m would be 450 m and constraints would barely hold.)
TS_INLINE float phi_d(float x, float d, float s, float lambda) {
    const float t = fmax(s * d, 1e-3f);
    const float b = -lambda / (3.0f * t * t);
    const float c = b * t * t * t + lambda * t;
    if (x < -t) return lambda * x + c;
    if (x > t) return lambda * x - c;
    return -b * x * x * x;
}

// kappa of a candidate at the coarsest level, which holds the share layout (kLayoutWeight in
// synth/initial_patches.h); own_exemplar < 0 elsewhere.
TS_INLINE float layout_kappa(float kappa, global const uchar* atlas_exemplar, int q, int own_exemplar) {
    return own_exemplar >= 0 && (int)atlas_exemplar[q] != own_exemplar ? kappa * LAYOUT_WEIGHT : kappa;
}

// Candidate prefetch (TS_CPU_PREFETCH, set by the host for CPU devices; results do not depend on
// it). A CPU device runs a work-group's items one after another, and each candidate's first
// appearance load was a cache miss that nothing overlapped: in `perf` of PoCL's `correct` 30% of
// its samples sat on that one load (docs/benchmarks.md, "Candidate prefetch"). With the prefetch,
// the sources are gathered first, every candidate's two rows of taps (q - 1 -/+ width) and those of
// the next work-item (lx + 2: inside a coherent patch its sources are these shifted by two) are
// touched, and only then are the candidates evaluated, in the same order. GPUs hide the latency
// with other warps; the gathered list would only take registers there.
#ifdef TS_CPU_PREFETCH
// A CPU driver whose compiler is not clang's has no __builtin_prefetch: it keeps the gathering,
// which alone changes nothing measurable, and the program still builds.
#if defined(__has_builtin)
#if __has_builtin(__builtin_prefetch)
#define TS_PREFETCH(pointer) __builtin_prefetch(pointer)
#endif
#endif
#ifndef TS_PREFETCH
#define TS_PREFETCH(pointer) ((void)(pointer))
#endif
TS_INLINE void prefetch_candidate(global const ushort4* appearance, int width, int q) {
    if (q < 0) return;  // no candidate (kNoIdentityCandidate)
    TS_PREFETCH(appearance + (q - 1 - width));
    TS_PREFETCH(appearance + (q - 1 + width));
}
#endif

// Eq. 7's comparison of one candidate against the best so far; the first of equal costs stays.
TS_INLINE void consider_candidate(global const ushort4* appearance, int width, const float4* ns, int q, float4 weight,
                                  float kappa, int median_offset, float* best_cost, int* best_q, float* best_h,
                                  bool* keep_v) {
    float h;
    const float cost = candidate_cost(appearance, width, ns, q, weight, kappa, *best_cost, median_offset, &h);
    if (cost < *best_cost) {
        *best_cost = cost;
        *best_q = q;
        *best_h = h;
        *keep_v = false;
    }
}

// Corrects the pixels of one parity class (one of the 4 subpasses), in place: a pixel of the class
// only reads pixels of other classes (and itself), so there are no races. Costs are evaluated in
// quantised appearance units weighted by scale^2 per mode: the metric distance of eq. 7 without
// dequantising every tap.
// Constraints (s5): `target_sets` (one uint per region pixel, 0 = any type) rejects candidates of
// other types, with seeding from the per-type lists when all are rejected (use_types 1), or on the
// finest levels (use_types 2) keeps the type of a pixel whose source has one of them, unseeded
// (constraints/constraint_fields.h); `blend` holds, per region
// pixel, the point and curve constraints' inverse-distance sums (sum b, sum b*h_t, sum b*d), which
// pull the chosen height towards the blended target with phi_d. `median_offset`: the level takes
// eq. 7's offset h as a median (candidate_cost). `lowest_height`: the floor of unconstrained heights
// (synth/level_ground.h, lowestExemplarHeight).
kernel void correct(global float4* state, Region region, int first_x, int first_y, int inset,
                    global const ushort4* appearance, global const uint2* similar, int width, float4 scale,
                    global const uint* target_sets, int use_types, global const uchar* atlas_type,
                    global const uint* type_seeds, global const int2* seed_ranges, uint seed_salt,
                    global const float4* blend, int use_blend, global const float* heights, global const uint* prev_index,
                    global const float* prev_v, global const uchar* coherence, int use_prev,
                    global const uchar* atlas_exemplar, global const uchar* layout, int use_layout,
                    global const uchar* level_ground, float level_tolerance, float lowest_height, int median_offset,
                    int atlas_pixels) {
    const int lx = first_x + 2 * (int)get_global_id(0), ly = first_y + 2 * (int)get_global_id(1);
    if (lx >= region.width - inset || ly >= region.height - inset) return;
    const int pixel = ly * region.width + lx;
    const float ceiling = state[pixel].w;
    if (use_prev && prev_index[pixel] != NO_PREVIOUS && coherence[pixel] == COHERENCE_FROZEN) {
        // s5.3 freeze: the previous result stands, offset included, whatever the neighbours do.
        const int q = (int)prev_index[pixel];
        state[pixel] = (float4)((float)(q % width), (float)(q / width), prev_v[pixel], ceiling);
        return;
    }
    const int2 diagonals[4] = {(int2)(-1, -1), (int2)(1, -1), (int2)(-1, 1), (int2)(1, 1)};
    const float inv_scale0 = 1.0f / scale.x;
    const float4 weight = scale * scale;
    float4 ns[4];
    for (int k = 0; k < 4; ++k) {
        const int dx = diagonals[k].x, dy = diagonals[k].y;
        const float4 g0 = neighbour_appearance_q(appearance, width, state_at(state, region, lx + dx, ly + dy), 0.0f, 0.0f, inv_scale0);
        const float4 g1 = neighbour_appearance_q(appearance, width, state_at(state, region, lx + 2 * dx, ly + dy), (float)dx, 0.0f, inv_scale0);
        const float4 g2 = neighbour_appearance_q(appearance, width, state_at(state, region, lx + dx, ly + 2 * dy), 0.0f, (float)dy, inv_scale0);
        const float third = 1.0f / 3.0f;
        ns[k] = (float4)((g0.x + g1.x + g2.x) * third, (g0.y + g1.y + g2.y) * third, (g0.z + g1.z + g2.z) * third,
                         (g0.w + g1.w + g2.w) * third);
    }
    uint target = use_types ? target_sets[pixel] : 0u;
    if (target != 0u && use_types == 2) {
        const float4 own = state[pixel];
        const uint type = atlas_type[floor_nonneg(own.y + 0.5f) * width + floor_nonneg(own.x + 0.5f)];
        if (type >= 32u || ((target >> type) & 1u) == 0u) target = 0u;
    }
    // The coarsest level holds the share layout (synth/initial_patches.h, kLayoutWeight): a
    // candidate from another exemplar than the pixel's share cell costs LAYOUT_WEIGHT times more.
    const int own_exemplar = use_layout ? (int)layout[pixel] : -1;
    float best_cost = INFINITY, best_h = 0.0f;
    int best_q = -1;
    bool keep_v = false;
    if (use_prev && prev_index[pixel] != NO_PREVIOUS &&
        (target == 0u || ((target >> atlas_type[prev_index[pixel]]) & 1u) != 0u)) {
        // s5.3: the previous result of this level and pass is the first candidate, its cost
        // multiplied by W; s5.2: only when it is of a painted type, so a repainted pixel can change.
        const int q = (int)prev_index[pixel];
        const uchar code = coherence[pixel];
        float h;
        best_cost = candidate_cost(appearance, width, ns, q, weight,
                                   layout_kappa(code == COHERENCE_FREE ? 1.0f : COHERENT_WEIGHT, atlas_exemplar, q, own_exemplar),
                                   INFINITY, median_offset, &h);
        best_q = q;
        best_h = h;
        // A coherent pixel that keeps its previous coordinate keeps its previous offset too, so
        // offsets do not drift away from an edit across the whole terrain.
        keep_v = code != COHERENCE_FREE;
    }
    // Inside a coherent patch all nine S(p + D) - D name the same pixel; evaluating it once gives
    // the same winner (ties keep the first), so repeated sources are skipped.
    int seen[9];
    int seen_count = 0;
#ifdef TS_CPU_PREFETCH
    int gathered_q[18];  // two candidates per distinct source, in evaluation order
    float gathered_kappa[18];
    int gathered = 0;
#endif
    for (int ddy = -1; ddy <= 1; ++ddy) {
        for (int ddx = -1; ddx <= 1; ++ddx) {
            const float4 s = state_at(state, region, lx + ddx, ly + ddy);
            const int cx = floor_nonneg(s.x - (float)ddx + 0.5f);
            const int cy = floor_nonneg(s.y - (float)ddy + 0.5f);
            const int c = cy * width + cx;
            bool repeated = false;
            for (int i = 0; i < seen_count; ++i) repeated = repeated || seen[i] == c;
            if (repeated) continue;
            seen[seen_count++] = c;
            // C_1(c) = c, none (-1) outside its exemplar's interior (kNoIdentityCandidate in
            // reference_kernels.h), C_2(c) from PatchMatch (s4), one load.
            const uint2 table = similar[c];
            const int candidates[2] = {(int)table.x, (int)table.y};
#ifdef TS_CPU_PREFETCH
            const uint2 next = similar[min(c + 2, atlas_pixels - 1)];
            prefetch_candidate(appearance, width, (int)next.x);
            prefetch_candidate(appearance, width, (int)next.y);
#endif
            for (int j = 0; j < 2; ++j) {
                const int q = candidates[j];
                if (q < 0) continue;
                if (target != 0u && ((target >> atlas_type[q]) & 1u) == 0u) continue;  // s5.2 rejection
                const float kappa = layout_kappa(j == 0 ? 1.0f : 2.0f, atlas_exemplar, q, own_exemplar);
#ifdef TS_CPU_PREFETCH
                prefetch_candidate(appearance, width, q);
                gathered_q[gathered] = q;
                gathered_kappa[gathered++] = kappa;
#else
                consider_candidate(appearance, width, ns, q, weight, kappa, median_offset, &best_cost, &best_q, &best_h, &keep_v);
#endif
            }
        }
    }
#ifdef TS_CPU_PREFETCH
    for (int i = 0; i < gathered; ++i)
        consider_candidate(appearance, width, ns, gathered_q[i], weight, gathered_kappa[i], median_offset, &best_cost,
                           &best_q, &best_h, &keep_v);
#endif
    const int gx = region.x + lx, gy = region.y + ly;
    if (best_q < 0 && use_types != 2) {
        // s5.2 seeding: nine random coordinates of each target type, from the preselected lists.
        for (int t = 0; t < 32; ++t) {
            if (((target >> t) & 1u) == 0u) continue;
            const int2 range = seed_ranges[t];
            for (int k = 0; k < SEEDS_PER_TYPE && range.y > 0; ++k) {
                const int q = (int)type_seeds[range.x + (int)(ts_hash3(gx * SEEDS_PER_TYPE + k, gy, seed_salt ^ (uint)t) % (uint)range.y)];
                float h;
                const float cost = candidate_cost(appearance, width, ns, q, weight,
                                                  layout_kappa(2.0f, atlas_exemplar, q, own_exemplar), best_cost,
                                                  median_offset, &h);
                if (cost < best_cost) {
                    best_cost = cost;
                    best_q = q;
                    best_h = h;
                }
            }
        }
    }
    if (best_q < 0) {
        // Every candidate was rejected (a painted type without seed coordinates at this level) or
        // costs too much to compare: the pixel keeps its own coordinate, C_1 of S(p).
        const float4 s = state[pixel];
        const int c = floor_nonneg(s.y + 0.5f) * width + floor_nonneg(s.x + 0.5f);
        best_q = (int)similar[c].x;
        if (best_q < 0) best_q = c;  // S(p) is interior after upsampling; never read outside the atlas
        float h = 0.0f;
        candidate_cost(appearance, width, ns, best_q, weight, 1.0f, INFINITY, median_offset, &h);
        best_h = h;
    }
    float v = keep_v ? prev_v[pixel] : best_h * scale.x;
    if (!keep_v && level_ground[best_q]) {
        // Level ground settles as water does (synth/level_ground.h): no higher than its lowest
        // neighbour copied from the same level ground (a level source of the same height).
        const float own = heights[best_q];
        float lowest = INFINITY;
        for (int ddy = -1; ddy <= 1; ++ddy)
            for (int ddx = -1; ddx <= 1; ++ddx) {
                if (ddx == 0 && ddy == 0) continue;
                const float4 s = state_at(state, region, lx + ddx, ly + ddy);
                const int q = floor_nonneg(s.y + 0.5f) * width + floor_nonneg(s.x + 0.5f);
                if (level_ground[q] && fabs(heights[q] - own) <= level_tolerance) lowest = fmin(lowest, heights[q] + s.z);
            }
        if (lowest < INFINITY) v = fmin(v, lowest - own);
    }
    const float4 sums = use_blend ? blend[pixel] : (float4)(0.0f);  // sum b, sum b*h_t, sum b*d (s5.1)
    const bool constrained = sums.x > 0.0f;
    if (constrained && !keep_v) {
        // h_c is the candidate's own height E(q) + V, not its neighbourhood mean (mode 0): on a
        // peak the mean sits below the centre, and pulling the mean would overshoot the site.
        const float candidate_height = heights[best_q] + v;
        v = v + phi_d(sums.y / sums.x - candidate_height, sums.z / sums.x, TOLERANCE_SLOPE, BLEND_SLOPE);
    }
    // Nothing below the exemplars' lowest ground (synth/level_ground.h, lowestExemplarHeight) but
    // what constraints ask for and the channels a coarser level carved (the ceiling, next).
    if (!keep_v && !constrained) v = fmax(v, lowest_height - heights[best_q]);
    // Drainage (issue 17): a channel carved at the coarser level (drainage_breach.h) stays at or
    // below the carved height however the candidates re-detail it; constraints win over channels.
    if (ceiling < INFINITY && !constrained) v = fmin(v, ceiling - heights[best_q]);
    state[pixel] = (float4)((float)(best_q % width), (float)(best_q / width), v, ceiling);
}

// Heights E(S) + V (bilinear in E) of the output window, and the sources when asked for.
kernel void resolve(global const float4* state, Region region, Region out, global const float* heights,
                    global const uchar* exemplar, global const int4* rects, int width, global float* out_heights,
                    global float* out_source, global uchar* out_exemplar, int want_sources) {
    const int x = get_global_id(0), y = get_global_id(1);
    if (x >= out.width || y >= out.height) return;
    const float4 s = state[(out.y - region.y + y) * region.width + (out.x - region.x + x)];
    const int ix = floor_nonneg(s.x), iy = floor_nonneg(s.y);  // atlas coordinates are never negative
    const float tx = s.x - (float)ix, ty = s.y - (float)iy;
    const int i = iy * width + ix;
    const float top = heights[i] + (heights[i + 1] - heights[i]) * tx;
    const float bot = heights[i + width] + (heights[i + width + 1] - heights[i + width]) * tx;
    const int o = y * out.width + x;
    out_heights[o] = top + (bot - top) * ty + s.z;
    if (want_sources) {
        const int e = exemplar[i];
        out_source[2 * o] = s.x - (float)rects[e].x;
        out_source[2 * o + 1] = s.y - (float)rects[e].y;
        out_exemplar[o] = (uchar)e;
    }
}
