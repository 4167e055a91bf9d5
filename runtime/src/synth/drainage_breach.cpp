#include "synth/drainage_breach.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>

#include "core/workers.h"

namespace terrasynth {

int breachRadius(int level) {
    // Pixels of the level: coarse levels are small and their basins span many kilometres. Level 0's
    // pits are small, and at R = 8 its margin (2R+1 pixels around the largest region) and its pass
    // over every pixel were about a third of the drainage's time; R = 2 keeps the gate figures
    // (seeds 3-8: 79 of 84 fluvial runs pass, as at 8) and the 512^2 depression test, which no
    // breach at level 0 misses (wn_big_butte; docs/realism.md, "Cost").
    static const int kRadius[] = {2, 8, 16, 24, 32};
    return kRadius[std::min(std::max(level, 0), 4)];
}

}  // namespace terrasynth

namespace terrasynth::synth {
namespace {

// Breach workers at most: the pits of a level are few and their searches short (docs/realism.md).
constexpr int kMaxBreachThreads = 8;

// One pit's search window: cost, predecessor, region pixel and state per cell of the (2R+1)^2
// square, stored with a ring of one cell around it that is never entered, so a cell's eight
// neighbours need no bounds test. Cells are numbered row-major in the ringed square, which orders
// them as the square's own row-major numbers do (the heap's and the edge's tie-breaks).
class PathSearch {
public:
    // Windows of `radius` in regions `region_width` pixels wide.
    PathSearch(int radius, int region_width)
        : radius_(radius), side_(2 * radius + 1), stride_(side_ + 2), cells_(stride_ * stride_), w_(region_width) {
        // The eight neighbours in the ringed square and in the region, and the steps' lengths.
        for (int k = 0, dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                if (!dx && !dy) continue;
                neighbour_[k] = dy * stride_ + dx, region_step_[k] = dy * w_ + dx;
                length_[k++] = dx && dy ? kBreachDiagonal : 1.0f;
            }
        cost_.resize(cells_);
        parent_.resize(cells_);
        region_index_.resize(cells_);
        reached_.assign(cells_, 0);
        done_.assign(cells_, 0);
        window_edge_.assign(cells_, 0);
        for (int cy = 0; cy < side_; ++cy)
            for (int cx = 0; cx < side_; ++cx)
                window_edge_[cellAt(cx, cy)] = cx == 0 || cy == 0 || cx == side_ - 1 || cy == side_ - 1;
    }

    // Region pixels of the cheapest path from the pit at (x, y) to a pixel `margin` lower, pit first;
    // else to the first strictly lower pixel the search met; else (to_edge) to the cheapest reached
    // cell on the window's edge; else empty. The path goes into `path`; false when empty.
    // window_min: the lowest height of the region within the radius of the pit. It changes no
    // result, only the work: when no pixel is `margin` lower, the whole window would be searched in
    // vain and the answer is the first lower pixel met, so the search stops there (at coarse levels
    // most searches are such, and they were most of the breach's time).
    bool find(const std::vector<float>& z, const std::vector<uint8_t>& fixed, int h, int x, int y, float margin,
              bool to_edge, float window_min, std::vector<int>& path) {
        const int w = w_;
        path.clear();
        const float bottom = z[y * w + x];
        const bool margin_reachable = window_min < bottom - margin;
        const bool lower_reachable = window_min < bottom;
        if (!to_edge && !lower_reachable) return false;
        int fallback = -1;
        // The cheapest settled, unprotected cell on the window's edge (ties: the lower cell index).
        // Cells settle in order of cost, so it is the first one settled, unless a cell of the same
        // cost but a lower index settles after it (a step can round to nothing on a long path). A
        // regional low (nothing lower in the window) ends there, so its search stops once the cost
        // grows past it.
        int edge = -1;
        nextSearch();
        closeOutside(w, h, x, y);
        open_.clear();
        const int centre = cellAt(radius_, radius_);
        reach(centre, 0.0f);
        parent_[centre] = -1;
        region_index_[centre] = y * w + x;
        push(entry(0.0f, centre));
        while (!open_.empty()) {
            const Entry top = pop();
            const float d = costOf(top);
            const int cell = cellOf(top);
            if (isDone(cell)) continue;
            if (!lower_reachable && edge >= 0 && d > cost_[edge]) return trace(edge, path);
            done_[cell] = search_;
            const int g = region_index_[cell];
            if (to_edge && window_edge_[cell] && !fixed[g] && (edge < 0 || (d == cost_[edge] && cell < edge))) edge = cell;
            if (z[g] < bottom - margin) return trace(cell, path);
            if (fallback < 0 && z[g] < bottom) {
                fallback = cell;
                // Popped cells are final, so this is the path an exhausted search would return.
                if (!margin_reachable) return trace(fallback, path);
            }
            if (cell != centre && fixed[g]) continue;  // may end a path, never carry one
            for (int k = 0; k < 8; ++k) {
                const int n = cell + neighbour_[k];
                if (isDone(n)) continue;  // settled, on the ring or outside the region
                const int gn = g + region_step_[k];
                const float step = (std::max(0.0f, z[gn] - bottom) + kBreachStepCost) * length_[k];
                if (reached_[n] != search_ || d + step < cost_[n]) {
                    reach(n, d + step);
                    parent_[n] = cell;
                    region_index_[n] = gn;
                    push(entry(cost_[n], n));
                }
            }
        }
        if (fallback >= 0) return trace(fallback, path);
        return trace(edge, path);  // empty when no edge cell (or no to_edge)
    }

private:
    // A binary min-heap on (cost, cell) packed into one integer: a cost is never negative, so its
    // float bits order as the cost does, and the cell breaks ties. A cell is pushed again only with
    // a lower cost, so no two entries are equal and the pop order is that of any heap.
    using Entry = uint64_t;
    static Entry entry(float cost, int cell) {
        uint32_t bits;
        std::memcpy(&bits, &cost, sizeof bits);
        return static_cast<Entry>(bits) << 32 | static_cast<uint32_t>(cell);
    }
    static float costOf(Entry e) {
        const uint32_t bits = static_cast<uint32_t>(e >> 32);
        float cost;
        std::memcpy(&cost, &bits, sizeof cost);
        return cost;
    }
    static int cellOf(Entry e) { return static_cast<int>(static_cast<uint32_t>(e)); }
    void push(Entry e) {
        open_.push_back(e);
        std::push_heap(open_.begin(), open_.end(), std::greater<Entry>());
    }
    Entry pop() {
        std::pop_heap(open_.begin(), open_.end(), std::greater<Entry>());
        const Entry e = open_.back();
        open_.pop_back();
        return e;
    }

    int cellAt(int cx, int cy) const { return (cy + 1) * stride_ + cx + 1; }

    // Cells carry the number of the search that last reached or settled them, so a new search
    // starts without clearing the window (at level 4, 67^2 cells per pit).
    void nextSearch() {
        if (++search_ == 0) {  // wrapped: stale stamps could match again
            std::fill(reached_.begin(), reached_.end(), 0);
            std::fill(done_.begin(), done_.end(), 0);
            search_ = 1;
        }
    }
    void reach(int cell, float cost) { cost_[cell] = cost, reached_[cell] = search_; }
    bool isDone(int cell) const { return done_[cell] == search_; }

    // Marks as settled the ring and the window's cells outside the region (pixel (x, y) is the
    // centre), so that no search enters them. Inside a synthesis plan the windows of the pits it
    // searches lie inside the region; only the ring is marked then.
    void closeOutside(int w, int h, int x, int y) {
        for (int i = 0; i < stride_; ++i) {
            done_[i] = done_[(stride_ - 1) * stride_ + i] = search_;
            done_[i * stride_] = done_[i * stride_ + stride_ - 1] = search_;
        }
        if (x >= radius_ && y >= radius_ && x + radius_ < w && y + radius_ < h) return;
        for (int cy = 0; cy < side_; ++cy)
            for (int cx = 0; cx < side_; ++cx) {
                const int gx = x + cx - radius_, gy = y + cy - radius_;
                if (gx < 0 || gy < 0 || gx >= w || gy >= h) done_[cellAt(cx, cy)] = search_;
            }
    }

    bool trace(int cell, std::vector<int>& path) const {
        for (; cell >= 0; cell = parent_[cell]) path.push_back(region_index_[cell]);
        std::reverse(path.begin(), path.end());
        return !path.empty();
    }

    int radius_, side_, stride_, cells_, w_;
    int neighbour_[8], region_step_[8];
    float length_[8];
    std::vector<float> cost_;
    std::vector<int> parent_, region_index_;
    std::vector<uint32_t> reached_, done_;  // search_ when reached (cost_ valid) / settled
    std::vector<uint8_t> window_edge_;       // 1 on the square's outer cells (DrainageInputs::carve_to_edge)
    uint32_t search_ = 0;
    std::vector<Entry> open_;
};

// Minimum of each run of 2r+1 values of a row centred on each element, clamped to the row (van
// Herk / Gil-Werman: per block of 2r+1, prefix and suffix minima; three comparisons per element).
void rowMinimum(const float* in, int n, int r, std::vector<float>& padded, std::vector<float>& prefix,
                std::vector<float>& suffix, float* out) {
    const int k = 2 * r + 1, m = (n + 2 * r + k - 1) / k * k;
    padded.assign(static_cast<size_t>(m), INFINITY);
    std::copy(in, in + n, padded.begin() + r);
    prefix.resize(static_cast<size_t>(m));
    suffix.resize(static_cast<size_t>(m));
    for (int i = 0; i < m; ++i) prefix[i] = i % k ? std::min(prefix[i - 1], padded[i]) : padded[i];
    for (int i = m - 1; i >= 0; --i) suffix[i] = (i + 1) % k ? std::min(suffix[i + 1], padded[i]) : padded[i];
    // Element i's run is padded[i .. i + 2r]: a block's suffix from i and the next block's prefix.
    for (int i = 0; i < n; ++i) out[i] = std::min(suffix[i], prefix[i + 2 * r]);
}

// Windows up to this radius take their minimum straight from z, (2r+1)^2 reads per pit; wider
// ones from sliding row minima, computed for every pixel (level 1 of a 1024^2 synthesis: 2019 pits at
// radius 8).
constexpr int kDirectMinimumRadius = 8;

// The lowest z within Chebyshev distance r of pixel (x, y), inside the region: what the pit's
// search window can reach at best (PathSearch::find's window_min). row_min: each row's minimum over
// 2r+1 columns (rowMinimum), or empty to read z.
float windowMinimum(const std::vector<float>& z, const std::vector<float>& row_min, int w, int h, int x, int y, int r) {
    float lowest = INFINITY;
    for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy) {
        const size_t row = static_cast<size_t>(yy) * w;
        if (!row_min.empty()) {
            lowest = std::min(lowest, row_min[row + x]);
            continue;
        }
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) lowest = std::min(lowest, z[row + xx]);
    }
    return lowest;
}

// The atlas pixel a pixel was copied from (its coordinate rounded).
size_t sourcePixel(const DatabaseLevel& db, const PixelState& s) {
    return static_cast<size_t>(std::lround(s.y)) * db.width + static_cast<size_t>(std::lround(s.x));
}

bool copiedFromClosedDepression(const DatabaseLevel& db, const PixelState& s) {
    const size_t q = sourcePixel(db, s);
    return q < db.closed.size() && db.closed[q];
}

// Whether the pixel was copied from an exemplar with real basins (DrainageInputs::basin_exemplars).
bool copiedFromBasinExemplar(const DatabaseLevel& db, const std::vector<uint8_t>* basin_exemplars, const PixelState& s) {
    if (!basin_exemplars) return false;
    const size_t q = sourcePixel(db, s);
    if (q >= db.exemplar.size()) return false;
    const uint8_t e = db.exemplar[q];
    return e < basin_exemplars->size() && (*basin_exemplars)[e];
}

// Marks the pits of row y between columns x0 and x1 (interior pixels): pixels lower than their 8
// neighbours in (height, row, column) order, where of two equal heights the earlier pixel is the
// lower, so an earlier neighbour must be strictly higher and a later one at least as high. All
// eight tests are evaluated for every pixel, without branches, so the loop vectorises (a pixel at a
// time, level 0's scan took longer than all its searches).
void markPits(const std::vector<float>& z, int w, int y, int x0, int x1, std::vector<uint8_t>& pit) {
    const float* up = &z[static_cast<size_t>(y - 1) * w];
    const float* row = up + w;
    const float* down = row + w;
    pit.resize(static_cast<size_t>(w));
    for (int x = x0; x <= x1; ++x) {
        const float c = row[x];
        pit[x] = (up[x - 1] > c) & (up[x] > c) & (up[x + 1] > c) & (row[x - 1] > c) & (row[x + 1] >= c) &
                 (down[x - 1] >= c) & (down[x] >= c) & (down[x + 1] >= c);
    }
}

// Whether path cell `cell`, `rise` metres above its pit, lies on the level ground the pit does
// (DrainageInputs::level_ground): both copied from level ground at the same source height.
bool onPitsLevelGround(const DatabaseLevel& db, const DrainageInputs& inputs, const PixelState* state, int pit, int cell,
                       float rise) {
    if (!inputs.level_ground || rise > inputs.level_tolerance) return false;
    const size_t p = sourcePixel(db, state[pit]), c = sourcePixel(db, state[cell]);
    const std::vector<uint8_t>& level = *inputs.level_ground;
    return level[p] && level[c] && std::fabs(db.height_m[c] - db.height_m[p]) <= inputs.level_tolerance;
}

// The cell carved beside a diagonal step of a path from region pixel `from` to `to`, so that the
// channel is 4-connected: one of the two pixels both touch by a side, the lower (ties: the one in
// `from`'s row), never a protected one; -1 for a straight step or when both are protected. Carved
// cells of a diagonal meet only at their corners, and a 45-degree channel across a flat floor read
// as a dashed line of pits at 1:1 (docs/realism.md, "Known weaknesses").
int diagonalCorner(const std::vector<float>& z, const std::vector<uint8_t>& fixed, int w, int from, int to) {
    const int dx = to % w - from % w, dy = to / w - from / w;
    if (dx == 0 || dy == 0) return -1;
    const int in_row = from + dx, in_column = from + dy * w;
    const bool row_open = !fixed[in_row], column_open = !fixed[in_column];
    if (row_open && column_open) return z[in_row] <= z[in_column] ? in_row : in_column;
    return row_open ? in_row : column_open ? in_column : -1;
}

}  // namespace

float breachDepthMargin(const DatabaseLevel& db) {
    std::vector<float> relief;
    for (int y = 1; y + 1 < db.height; y += 2)
        for (int x = 1; x + 1 < db.width; x += 2) {
            const size_t i = static_cast<size_t>(y) * db.width + x;
            if (db.type[i] == kNoType) continue;  // gutter
            float lo = db.height_m[i], hi = lo;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const float v = db.height_m[i + dy * db.width + dx];
                    lo = std::min(lo, v), hi = std::max(hi, v);
                }
            relief.push_back(hi - lo);
        }
    if (relief.empty()) return 0.0f;
    std::nth_element(relief.begin(), relief.begin() + relief.size() / 2, relief.end());
    return kBreachDepthFraction * relief[relief.size() / 2];
}

std::vector<uint8_t> exemplarsWithRealBasins(const ExemplarDatabase& db) {
    if (db.levels.empty()) return {};
    const DatabaseLevel& level0 = db.levels[0];
    std::vector<size_t> pixels(db.exemplars.size(), 0), closed(db.exemplars.size(), 0);
    for (size_t i = 0; i < level0.exemplar.size() && i < level0.closed.size(); ++i) {
        const uint8_t e = level0.exemplar[i];
        if (e >= pixels.size()) continue;  // padding
        ++pixels[e];
        closed[e] += level0.closed[i] ? 1 : 0;
    }
    std::vector<uint8_t> real(pixels.size(), 0);
    for (size_t e = 0; e < pixels.size(); ++e)
        real[e] = pixels[e] > 0 && static_cast<double>(closed[e]) >= kRealBasinShare * static_cast<double>(pixels[e]);
    return real;
}

const std::vector<uint8_t>& DepthMargins::basinExemplars(const ExemplarDatabase& db) {
    if (!basins_known_) basin_exemplars_ = exemplarsWithRealBasins(db), basins_known_ = true;
    return basin_exemplars_;
}

float DepthMargins::at(const ExemplarDatabase& db, int level) {
    if (margins_.size() != db.levels.size()) margins_.assign(db.levels.size(), 0.0f), known_.assign(db.levels.size(), 0);
    // No finer level follows level 0, so its paths need only reach the first lower pixel.
    if (!known_[level]) margins_[level] = level > 0 ? breachDepthMargin(db.levels[level]) : 0.0f, known_[level] = 1;
    return margins_[level];
}

BreachCounts breachPits(const DatabaseLevel& db, const LevelRegion& region, int radius, const DrainageInputs& inputs,
                        PixelState* state, BreachScratch* scratch) {
    const int w = region.width, h = region.height;
    const size_t pixels = region.pixels();
    BreachScratch own;
    BreachScratch& buffers = scratch ? *scratch : own;
    std::vector<uint8_t>& fixed = buffers.fixed;
    // Frozen pixels take the recorded post-breach state; frozen and constrained pixels are never carved.
    holdFrozenAndConstrained(db, inputs.coherence, inputs.drained, inputs.blend, pixels, state, fixed);
    // Pits that can reach the needed pixels: within `radius` of them (interior pixels only).
    int x0 = 1, y0 = 1, x1 = w - 2, y1 = h - 2;
    if (inputs.needed.width > 0 && inputs.needed.height > 0) {
        x0 = std::max(x0, inputs.needed.x - region.x - radius), y0 = std::max(y0, inputs.needed.y - region.y - radius);
        x1 = std::min(x1, inputs.needed.x - region.x + inputs.needed.width - 1 + radius);
        y1 = std::min(y1, inputs.needed.y - region.y + inputs.needed.height - 1 + radius);
    }

    const int threads = std::min({hardwareThreads(), kMaxBreachThreads, std::max(1, h / 8)});
    // Heights, and for wide windows each row's minimum over 2 * radius + 1 columns, where the
    // searches read them: within radius + 1 of the pits (at level 4 of a 1024^2 synthesis, 67% of
    // the region). Every pixel's ceiling becomes +inf in the same pass over the state (the carves
    // set theirs below): a pass of its own over the state cost about as much as the heights.
    const int zx0 = std::max(0, x0 - radius - 1), zx1 = std::min(w - 1, x1 + radius + 1);
    const int zy0 = std::max(0, y0 - radius - 1), zy1 = std::min(h - 1, y1 + radius + 1);
    std::vector<float>& z = buffers.z;
    std::vector<float>& row_min = buffers.row_min;
    z.resize(pixels);
    row_min.resize(radius > kDirectMinimumRadius ? pixels : 0);
    runOnWorkers(threads, [&](int t) {
        std::vector<float> padded, prefix, suffix;
        for (int y = t; y < h; y += threads) {
            PixelState* row_state = &state[static_cast<size_t>(y) * w];
            if (y >= zy0 && y <= zy1 && zx0 <= zx1) {
                float* row = &z[static_cast<size_t>(y) * w];
                for (int x = zx0; x <= zx1; ++x) row[x] = pixelHeight(db, row_state[x]);
                // The sub-row's own ends clamp a window only where the region's ends would.
                if (!row_min.empty())
                    rowMinimum(row + zx0, zx1 - zx0 + 1, radius, padded, prefix, suffix,
                               &row_min[static_cast<size_t>(y) * w + zx0]);
            }
            // Most ceilings are +inf already (finite only under the coarser level's carves); a
            // line of the state left unwritten is not written back.
            for (int x = 0; x < w; ++x)
                if (row_state[x].ceiling != INFINITY) row_state[x].ceiling = INFINITY;
        }
    });

    // Workers take the rows of pits in turn from a shared counter (pits and long searches cluster,
    // so fixed shares of rows keep one worker waiting for the other) and list their carves (pixel,
    // ceiling); the lowest carve of a pixel wins, whatever the order or the worker.
    struct Worker {
        std::vector<std::pair<int, float>> carves;
        BreachCounts counts;
    };
    std::vector<Worker> workers(static_cast<size_t>(threads));
    std::atomic<int> next_row{y0};
    auto work = [&](int t) {
        Worker& out = workers[static_cast<size_t>(t)];
        PathSearch search(radius, w);
        std::vector<int> path;
        std::vector<uint8_t> pit;
        for (int y = next_row++; y <= y1; y = next_row++) {
            markPits(z, w, y, x0, x1, pit);
            // About one pixel in a hundred is a pit: memchr skips the rest many bytes at a time.
            for (int x = x0; x <= x1; ++x) {
                const void* next_pit = std::memchr(&pit[x], 1, static_cast<size_t>(x1 - x + 1));
                if (!next_pit) break;
                x = static_cast<int>(static_cast<const uint8_t*>(next_pit) - pit.data());
                ++out.counts.pits;
                if (copiedFromClosedDepression(db, state[y * w + x])) continue;  // a real basin: keep it
                const float window_min = windowMinimum(z, row_min, w, h, x, y, radius);
                // A regional low of an exemplar with real basins is one of them: kept.
                const bool to_edge = inputs.carve_to_edge &&
                                     !(window_min >= z[y * w + x] && copiedFromBasinExemplar(db, inputs.basin_exemplars, state[y * w + x]));
                if (!search.find(z, fixed, h, x, y, inputs.depth_margin, to_edge, window_min, path)) continue;
                ++out.counts.breached;
                // A straight profile from the pit down, kBreachProfileDepth of the way to the lower
                // pixel; cells already below it stay. A path to the window's edge (carve_to_edge)
                // ends below the pit.
                const float top = z[path.front()];
                const float bottom = z[path.back()] < top ? z[path.back()] : top - std::max(inputs.depth_margin, kEdgeDrop);
                const float drop = (top - bottom) * kBreachProfileDepth;
                const float k = static_cast<float>(path.size() - 1);
                for (size_t i = 0; i < path.size(); ++i) {
                    if (onPitsLevelGround(db, inputs, state, path[0], path[i], z[path[i]] - top)) continue;
                    const float line = top - drop * (static_cast<float>(i) / k);
                    // + 0.0f: a carve of -0 is +0, so the lowest carve is one value whatever the order.
                    out.carves.push_back({path[i], std::min(z[path[i]], line) + 0.0f});
                    if (i == 0) continue;
                    const int corner = diagonalCorner(z, fixed, w, path[i - 1], path[i]);
                    if (corner < 0) continue;
                    const float midway = top - drop * ((static_cast<float>(i) - 0.5f) / k);
                    out.carves.push_back({corner, std::min(z[corner], midway) + 0.0f});
                }
            }
        }
    };
    runOnWorkers(threads, work);

    // Every pixel's ceiling is +inf but where carved: the carves go into the state's ceilings first
    // (lowest wins), then the carved pixels are lowered to them.
    BreachCounts counts;
    for (const Worker& worker : workers) {
        counts.pits += worker.counts.pits, counts.breached += worker.counts.breached;
        for (const auto& [pixel, carve] : worker.carves) state[pixel].ceiling = std::min(state[pixel].ceiling, carve);
    }
    for (const Worker& worker : workers)
        for (const auto& [pixel, carve] : worker.carves) {
            PixelState& s = state[pixel];
            // z takes the ceiling so that a pixel carved by several paths is lowered once.
            if (s.ceiling < z[pixel] && carve == s.ceiling) s.v = s.v - (z[pixel] - s.ceiling), z[pixel] = s.ceiling;
        }
    return counts;
}

}  // namespace terrasynth::synth
