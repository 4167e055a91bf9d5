// Drainage by bounded least-cost breaching on the device: the same rules, the same float operations
// in the same order as the C++ reference, runtime/src/synth/drainage_breach.cpp (breachPits), which
// explains them; runtime/src/cl/cl_drainage.cpp enqueues these kernels.
//
// One breach of a level's region runs these kernels, the state staying on the device:
//   breach_prepare     frozen pixels take their recorded post-breach state; no ceiling; where the
//                      searches read: protected flags, the heights E(S) + V, no carve yet
//   breach_row_min     (wide windows) each row's minimum over 2R+1 columns
//   breach_pit_flags   pits of the searched rectangle, flagged
//   breach_list_pits   the flagged pits, row by row, appended to a list (atomic counter)
//   breach_search      a few work-items take pits from the list in turn and search each one's
//                      least-cost path in scratch of their own; carves combine with atomic_min, and
//                      the first carve of a pixel lists it
//   breach_apply       the lowest carve of each listed pixel becomes its ceiling and lowers its V
// Nothing depends on which work-item searched which pit or in which order (the lowest carve wins),
// so the list's order, set by the atomic counter, changes no bit.
// The state is read and written as 4 floats per pixel (synth::PixelState: S.x, S.y, V, ceiling),
// not as float4: CPU drivers (PoCL) vectorise a kernel across work-items only without vector types.
//
// Host constants, passed as -D so they live in one place (synth/drainage_breach.h):
// BREACH_EDGE_DROP (kEdgeDrop), BREACH_STEP_COST (kBreachStepCost), DIAGONAL_LENGTH (kBreachDiagonal),
// BREACH_PROFILE_DEPTH (kBreachProfileDepth).

#pragma OPENCL FP_CONTRACT OFF

#ifndef BREACH_EDGE_DROP
#define BREACH_EDGE_DROP 1.0f
#endif
#ifndef BREACH_STEP_COST
#define BREACH_STEP_COST 1e-3f
#endif
#ifndef BREACH_PROFILE_DEPTH
#define BREACH_PROFILE_DEPTH 0.875f
#endif
#ifndef DIAGONAL_LENGTH
#define DIAGONAL_LENGTH 1.41421356f
#endif
#define BREACH_NO_PREVIOUS 0xffffffffu
#define BREACH_FROZEN 0
// An order-preserving int image of a float's bits (for atomic_min): negative floats have their
// magnitude bits flipped. +inf's image is the "no carve" value.
#define NO_CARVE 0x7f800000

typedef struct {
    int x, y, width, height;
} BreachRegion;

// The rectangle of region pixels [x0, x1] x [y0, y1], inclusive.
typedef struct {
    int x0, y0, x1, y1;
} Span;

TS_INLINE int ordered_key(float v) {
    const int bits = as_int(v);
    return bits >= 0 ? bits : bits ^ 0x7fffffff;
}
TS_INLINE float from_ordered_key(int key) { return as_float(key >= 0 ? key : key ^ 0x7fffffff); }

TS_INLINE float lerp_f(float a, float b, float t) { return a + (b - a) * t; }

// E(S) + V of a pixel (pixelHeight in synth/reference_kernels.h): one tap at whole atlas pixels,
// bilinear elsewhere.
TS_INLINE float breach_pixel_height(global const float* heights, int width, float sx, float sy, float v) {
    const int ix = (int)sx, iy = (int)sy;  // atlas coordinates are >= 0
    if ((float)ix == sx && (float)iy == sy) return heights[iy * width + ix] + v;
    const float fx = floor(sx), fy = floor(sy);
    const float tx = sx - fx, ty = sy - fy;
    const int i = (int)fy * width + (int)fx;
    const float top = lerp_f(heights[i], heights[i + 1], tx);
    const float bot = lerp_f(heights[i + width], heights[i + width + 1], tx);
    return lerp_f(top, bot, ty) + v;
}

// The atlas pixel a pixel was copied from (its coordinate rounded, halves away from zero).
TS_INLINE uint source_pixel(global const float* state, int i, int width) {
    return (uint)round(state[4 * i + 1]) * (uint)width + (uint)round(state[4 * i]);
}

// Per region pixel: frozen pixels (W = 0) with a recorded post-breach state take it (takePrevious)
// and every ceiling becomes +inf (the carves set theirs). Inside `zone` (where the searches read):
// frozen or constrained pixels are protected (`fixed`, when use_fixed), no carve yet, and the height.
kernel void breach_prepare(global float* state, BreachRegion region, global float* z, global uchar* fixed,
                           int use_fixed, global int* carve, Span zone, global const float* heights, int width,
                           global const uchar* coherence, int use_coherence, global const uint* drained_index,
                           global const float* drained_v, int use_drained, global const float* blend, int use_blend) {
    const int x = get_global_id(0), y = get_global_id(1);
    if (x >= region.width || y >= region.height) return;
    const int i = y * region.width + x;
    const bool frozen = use_coherence && coherence[i] == BREACH_FROZEN;
    if (frozen && use_drained && drained_index[i] != BREACH_NO_PREVIOUS) {
        const uint q = drained_index[i];
        state[4 * i] = (float)(q % (uint)width);
        state[4 * i + 1] = (float)(q / (uint)width);
        state[4 * i + 2] = drained_v[i];
    }
    if (state[4 * i + 3] != INFINITY) state[4 * i + 3] = INFINITY;  // most are +inf already: no write
    if (x < zone.x0 || x > zone.x1 || y < zone.y0 || y > zone.y1) return;
    if (use_fixed) fixed[i] = frozen || (use_blend && blend[4 * i] > 0.0f);
    carve[i] = NO_CARVE;
    z[i] = breach_pixel_height(heights, width, state[4 * i], state[4 * i + 1], state[4 * i + 2]);
}

// Each zone row's minimum over columns x - radius .. x + radius inside the zone (the zone's ends clamp
// a window only where the region's would, for the pits' windows), one work-item per row: per block
// of 2 * radius + 1 columns, suffix minima backwards into row_min, then prefix minima forwards,
// combined in place (van Herk / Gil-Werman: two passes, whatever the radius).
kernel void breach_row_min(global const float* z, BreachRegion region, Span zone, int radius, global float* row_min) {
    const int y = zone.y0 + (int)get_global_id(0);
    if (y > zone.y1) return;
    const int n = zone.x1 - zone.x0 + 1, k = 2 * radius + 1, m = (n + 2 * radius + k - 1) / k * k;
    const global float* in = z + y * region.width + zone.x0;
    global float* out = row_min + y * region.width + zone.x0;
    // Padded position p holds in[p - radius] (+inf outside the row); element i's window is p = i .. i + 2r.
    float suffix = INFINITY;
    for (int p = m - 1; p >= 0; --p) {
        const float v = p >= radius && p - radius < n ? in[p - radius] : INFINITY;
        suffix = (p + 1) % k ? fmin(suffix, v) : v;
        if (p < n) out[p] = suffix;
    }
    float prefix = INFINITY;
    for (int p = 0; p < n + 2 * radius; ++p) {
        const float v = p >= radius && p - radius < n ? in[p - radius] : INFINITY;
        prefix = p % k ? fmin(prefix, v) : v;
        if (p >= 2 * radius) out[p - 2 * radius] = fmin(out[p - 2 * radius], prefix);
    }
}

// Pits of `pits_span`: pixels lower than their 8 neighbours in (height, row, column) order (an
// earlier neighbour must be strictly higher, a later one at least as high), less those copied from
// a closed depression of their exemplar (real basins, kept); 1 in `flags` (per region pixel).
kernel void breach_pit_flags(global const float* z, global const float* state, BreachRegion region, Span pits_span,
                             global const uchar* closed, uint closed_pixels, int width, global uchar* flags) {
    const int x = pits_span.x0 + (int)get_global_id(0), y = pits_span.y0 + (int)get_global_id(1);
    if (x > pits_span.x1 || y > pits_span.y1) return;
    const int w = region.width;
    const global float* up = z + (y - 1) * w;
    const global float* row = up + w;
    const global float* down = row + w;
    const float c = row[x];
    bool pit = (up[x - 1] > c) & (up[x] > c) & (up[x + 1] > c) & (row[x - 1] > c) & (row[x + 1] >= c) &
               (down[x - 1] >= c) & (down[x] >= c) & (down[x + 1] >= c);
    if (pit) {  // about one pixel in a hundred: only its source is read
        const uint q = source_pixel(state, y * w + x, width);
        if (q < closed_pixels && closed[q]) pit = false;  // a real basin: kept
    }
    flags[y * w + x] = pit;
}

// The flagged pits of each row of `pits_span` (one work-item per row), appended to `pits`;
// counters[0] counts them.
kernel void breach_list_pits(global const uchar* flags, BreachRegion region, Span pits_span, global int* pits,
                             volatile global int* counters) {
    const int y = pits_span.y0 + (int)get_global_id(0);
    if (y > pits_span.y1) return;
    const global uchar* row = flags + y * region.width;
    int found = 0;
    for (int x = pits_span.x0; x <= pits_span.x1; ++x) found += row[x];
    if (found == 0) return;
    int at = atomic_add(&counters[0], found);
    for (int x = pits_span.x0; x <= pits_span.x1; ++x)
        if (row[x]) pits[at++] = y * region.width + x;
}

// The lowest height of the region within Chebyshev distance `radius` of pixel (x, y): what the pit's
// search window can reach at best. From the row minima when given, else straight from z.
TS_INLINE float window_minimum(global const float* z, global const float* row_min, int use_row_min, int w, int h,
                               int x, int y, int radius) {
    float lowest = INFINITY;
    const int ya = max(0, y - radius), yb = min(h - 1, y + radius);
    const int xa = max(0, x - radius), xb = min(w - 1, x + radius);
    for (int yy = ya; yy <= yb; ++yy) {
        if (use_row_min) {
            lowest = fmin(lowest, row_min[yy * w + x]);
            continue;
        }
        for (int xx = xa; xx <= xb; ++xx) lowest = fmin(lowest, z[yy * w + xx]);
    }
    return lowest;
}

// A search's scratch: worker t's cells lie together, from t * cells (a long search touches cells
// near each other, which then share cache lines; the longest searches set a level's time).
typedef struct {
    global float* cost;
    global uint* mark;     // 2 * serial: reached (cost valid, in the heap); 2 * serial + 1: settled
    global uchar* parent;  // the step (0-7) that reached the cell
    global int* heap_pos;  // the cell's place in the heap while it is there
    global ulong* heap;    // (cost bits, cell) packed: a cost is never negative, so its bits order as it does
    size_t base;           // the worker's first cell
} Scratch;

#define AT(scratch, cell) ((scratch).base + (size_t)(cell))

TS_INLINE ulong heap_entry(float cost, int cell) { return ((ulong)as_uint(cost) << 32) | (uint)cell; }

TS_INLINE void heap_place(Scratch s, int i, ulong e) {
    s.heap[AT(s, i)] = e;
    s.heap_pos[AT(s, (int)(uint)e)] = i;
}

TS_INLINE void heap_sift_up(Scratch s, int i, ulong e) {
    while (i > 0) {
        const int p = (i - 1) >> 1;
        const ulong pe = s.heap[AT(s, p)];
        if (pe <= e) break;
        heap_place(s, i, pe);
        i = p;
    }
    heap_place(s, i, e);
}

// Removes and returns the least entry of a heap of `count` > 0 entries.
TS_INLINE ulong heap_pop(Scratch s, int* count) {
    const ulong top = s.heap[AT(s, 0)];
    const int n = --*count;
    if (n == 0) return top;
    const ulong e = s.heap[AT(s, n)];
    int i = 0;
    for (;;) {
        const int l = 2 * i + 1;
        if (l >= n) break;
        const int r = l + 1;
        int m = l;
        ulong me = s.heap[AT(s, l)];
        if (r < n) {
            const ulong re = s.heap[AT(s, r)];
            if (re < me) m = r, me = re;
        }
        if (e <= me) break;
        heap_place(s, i, me);
        i = m;
    }
    heap_place(s, i, e);
    return top;
}

// One pit's least-cost search (PathSearch::find in drainage_breach.cpp): the window cell of the
// path's end, or -1. Cells are numbered row-major in the (2R+1)^2 window, which orders them as the
// reference's ringed numbering does (the heap's and the edge's tie-breaks). The heap keeps one
// entry per reached cell and lowers it when the cell's cost falls; the reference pushes a new entry
// instead and skips the stale ones: both pop the same cells in the same order (the entries are
// distinct, and a stale entry sorts after its cell's live one).
TS_INLINE int search_path(global const float* z, global const uchar* fixed, int use_fixed, int w, int h, int px, int py, int radius,
                          float margin, bool to_edge, float window_min, uint serial, Scratch s) {
    const float bottom = z[py * w + px];
    const float target = bottom - margin;
    const bool margin_reachable = window_min < target;
    const bool lower_reachable = window_min < bottom;
    if (!to_edge && !lower_reachable) return -1;
    const int side = 2 * radius + 1;
    const uint reached = 2u * serial, settled = 2u * serial + 1u;
    const int dxs[8] = {-1, 0, 1, -1, 1, -1, 0, 1}, dys[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
    int fallback = -1, edge = -1;
    float edge_cost = 0.0f;
    const int centre = radius * side + radius;
    s.cost[AT(s, centre)] = 0.0f;
    s.mark[AT(s, centre)] = reached;
    s.parent[AT(s, centre)] = 8;
    int count = 1;
    heap_place(s, 0, heap_entry(0.0f, centre));
    while (count > 0) {
        const ulong top = heap_pop(s, &count);
        const float d = as_float((uint)(top >> 32));
        const int cell = (int)(uint)top;
        if (!lower_reachable && edge >= 0 && d > edge_cost) return edge;
        s.mark[AT(s, cell)] = settled;
        const int cx = cell % side, cy = cell / side;
        const int gx = px + cx - radius, gy = py + cy - radius;
        const int g = gy * w + gx;
        const bool on_edge = cx == 0 || cy == 0 || cx == side - 1 || cy == side - 1;
        const bool is_fixed = use_fixed && fixed[g];
        if (to_edge && on_edge && !is_fixed && (edge < 0 || (d == edge_cost && cell < edge))) edge = cell, edge_cost = d;
        const float zg = z[g];
        if (zg < target) return cell;
        if (fallback < 0 && zg < bottom) {
            fallback = cell;
            // Settled cells are final, so this is the path an exhausted search would return.
            if (!margin_reachable) return fallback;
        }
        if (cell != centre && is_fixed) continue;  // may end a path, never carry one
        for (int k = 0; k < 8; ++k) {
            const int ncx = cx + dxs[k], ncy = cy + dys[k];
            if (ncx < 0 || ncy < 0 || ncx >= side || ncy >= side) continue;  // outside the window
            const int ngx = gx + dxs[k], ngy = gy + dys[k];
            if (ngx < 0 || ngy < 0 || ngx >= w || ngy >= h) continue;  // outside the region
            const int n = ncy * side + ncx;
            const uint m = s.mark[AT(s, n)];
            if (m == settled) continue;
            const float rise = z[ngy * w + ngx] - bottom;
            const float step = ((rise > 0.0f ? rise : 0.0f) + BREACH_STEP_COST) * (dxs[k] != 0 && dys[k] != 0 ? DIAGONAL_LENGTH : 1.0f);
            const float nd = d + step;
            if (m != reached) {
                s.cost[AT(s, n)] = nd;
                s.mark[AT(s, n)] = reached;
                s.parent[AT(s, n)] = (uchar)k;
                heap_sift_up(s, count++, heap_entry(nd, n));
            } else if (nd < s.cost[AT(s, n)]) {
                s.cost[AT(s, n)] = nd;
                s.parent[AT(s, n)] = (uchar)k;
                heap_sift_up(s, s.heap_pos[AT(s, n)], heap_entry(nd, n));
            }
        }
    }
    return fallback >= 0 ? fallback : edge;  // -1 when no edge cell (or no to_edge)
}

// The cell carved beside a diagonal step from `from` to `to` (region pixels), so that the channel
// is 4-connected: of the two pixels both touch by a side the lower (ties: the one in `from`'s row),
// never a protected one; -1 for a straight step or when both are protected (diagonalCorner in
// synth/drainage_breach.cpp).
TS_INLINE int diagonal_corner(global const float* z, global const uchar* fixed, int use_fixed, int w, int from, int to) {
    const int dx = to % w - from % w, dy = to / w - from / w;
    if (dx == 0 || dy == 0) return -1;
    const int in_row = from + dx, in_column = from + dy * w;
    const bool row_open = !(use_fixed && fixed[in_row]), column_open = !(use_fixed && fixed[in_column]);
    if (row_open && column_open) return z[in_row] <= z[in_column] ? in_row : in_column;
    return row_open ? in_row : (column_open ? in_column : -1);
}

// The searches: `workers` work-items take the listed pits in turn (counters[1]) and carve each path
// found to a straight profile from the pit down to its end (atomic_min of the carved heights); the
// first carve of a pixel appends it to `carved` (counters[2] counts them). serial_base + the pit's
// place in the list numbers its search in the scratch marks.
kernel void breach_search(global const float* z, global const uchar* fixed, int use_fixed, global const float* row_min,
                          int use_row_min, global const float* state, BreachRegion region, int radius, float margin,
                          int carve_to_edge, global const uchar* atlas_exemplar, uint atlas_pixels, int width,
                          global const uchar* basin_exemplars, uint basin_count, global const int* pits,
                          volatile global int* counters, uint serial_base, global float* cost, global uint* mark,
                          global uchar* parent, global int* heap_pos, global ulong* heap,
                          volatile global int* carve, global int* carved, global const float* heights,
                          global const uchar* level_ground, int use_level_ground, float level_tolerance) {
    const int w = region.width, h = region.height, side = 2 * radius + 1;
    const Scratch s = {cost, mark, parent, heap_pos, heap, get_global_id(0) * (size_t)(side * side)};
    const int count = counters[0];
    const int dxs[8] = {-1, 0, 1, -1, 1, -1, 0, 1}, dys[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
    for (int p = atomic_inc(&counters[1]); p < count; p = atomic_inc(&counters[1])) {
        const int pit = pits[p];
        const int px = pit % w, py = pit / w;
        const float bottom = z[pit];
        const float window_min = window_minimum(z, row_min, use_row_min, w, h, px, py, radius);
        // A regional low of an exemplar with real basins is one of them: kept.
        bool to_edge = carve_to_edge != 0;
        if (to_edge && window_min >= bottom) {
            const uint q = source_pixel(state, pit, width);
            if (q < atlas_pixels) {
                const uint e = atlas_exemplar[q];
                if (e < basin_count && basin_exemplars[e]) to_edge = false;
            }
        }
        const int end = search_path(z, fixed, use_fixed, w, h, px, py, radius, margin, to_edge, window_min,
                                    serial_base + (uint)p, s);
        if (end < 0) continue;
        // A straight profile from the pit down, BREACH_PROFILE_DEPTH of the way to the lower pixel;
        // cells already below it stay. A path to the window's edge ends below the pit.
        int cells = 0;
        for (int c = end; c != radius * side + radius; ++cells) {
            const int k = s.parent[AT(s, c)];
            c -= dys[k] * side + dxs[k];
        }
        const int end_pixel = pit + (end / side - radius) * w + (end % side - radius);
        const float top = bottom;
        const float lowest = z[end_pixel] < top ? z[end_pixel] : top - (margin < BREACH_EDGE_DROP ? BREACH_EDGE_DROP : margin);
        const float drop = (top - lowest) * BREACH_PROFILE_DEPTH;
        const float k_last = (float)cells;
        const uint pit_source = source_pixel(state, pit, width);
        const bool pit_level = use_level_ground && level_ground[pit_source];
        int c = end;
        for (int i = cells; i >= 0; --i) {
            const int g = pit + (c / side - radius) * w + (c % side - radius);
            const float line = top - drop * ((float)i / k_last);
            const float zg = z[g];
            // The level ground the pit lies in stays level (onPitsLevelGround in drainage_breach.cpp).
            const uint cell_source = source_pixel(state, g, width);
            const bool level = pit_level && zg - top <= level_tolerance && level_ground[cell_source] &&
                               fabs(heights[cell_source] - heights[pit_source]) <= level_tolerance;
            // + 0.0f: a carve of -0 counts as +0, so equal carves are equal keys.
            if (!level && atomic_min(&carve[g], ordered_key((line < zg ? line : zg) + 0.0f)) == NO_CARVE)
                carved[atomic_inc(&counters[2])] = g;
            if (i > 0) {
                const int k = s.parent[AT(s, c)];
                c -= dys[k] * side + dxs[k];
                // The step from the parent (path cell i - 1) to g; a diagonal one carves a corner too
                // (unless g is not carved).
                const int corner = level ? -1 : diagonal_corner(z, fixed, use_fixed, w, g - dys[k] * w - dxs[k], g);
                if (corner >= 0) {
                    const float midway = top - drop * (((float)i - 0.5f) / k_last);
                    const float zc = z[corner];
                    if (atomic_min(&carve[corner], ordered_key((midway < zc ? midway : zc) + 0.0f)) == NO_CARVE)
                        carved[atomic_inc(&counters[2])] = corner;
                }
            }
        }
    }
}

// Each carved pixel's ceiling becomes its lowest carve, and a pixel below its height is lowered to
// it, by V. `workers` work-items share the list.
kernel void breach_apply(global float* state, global const float* z, global const int* carve,
                         global const int* carved, global const int* counters) {
    const int count = counters[2];
    for (int j = get_global_id(0); j < count; j += get_global_size(0)) {
        const int i = carved[j];
        const float ceiling = from_ordered_key(carve[i]);
        const float zi = z[i];
        if (ceiling < zi) state[4 * i + 2] = state[4 * i + 2] - (zi - ceiling);
        state[4 * i + 3] = ceiling;
    }
}
