#include "synth/drainage_breach.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <thread>

namespace terrasynth {

int breachRadius(int level) {
    // Pixels of the level: coarse levels are small and their basins span many kilometres.
    static const int kRadius[] = {8, 8, 16, 24, 32};
    return kRadius[std::min(std::max(level, 0), 4)];
}

}  // namespace terrasynth

namespace terrasynth::synth {
namespace {

// Frozen pixels take the recorded post-breach state; frozen and constrained pixels are never carved.
std::vector<uint8_t> protectedPixels(const DatabaseLevel& db, const DrainageInputs& in, std::vector<PixelState>& state) {
    std::vector<uint8_t> fixed(state.size(), 0);
    const bool coherence = in.coherence && in.coherence->size() == state.size();
    const bool drained = in.drained && in.drained->index.size() == state.size();
    const bool blend = in.blend && in.blend->size() == 4 * state.size();
    for (size_t i = 0; i < state.size(); ++i) {
        if (coherence && (*in.coherence)[i] == static_cast<uint8_t>(Coherence::Frozen)) {
            fixed[i] = 1;
            if (drained && in.drained->index[i] != kNoPrevious) takePrevious(db, *in.drained, i, state[i]);
        }
        if (blend && (*in.blend)[4 * i] > 0.0f) fixed[i] = 1;
    }
    return fixed;
}

// One pit's search window: cost, predecessor and state per cell of the (2R+1)^2 square.
class PathSearch {
public:
    explicit PathSearch(int radius) : radius_(radius), side_(2 * radius + 1), cells_(side_ * side_) {
        cost_.resize(cells_);
        parent_.resize(cells_);
        done_.resize(cells_);
    }

    // Region pixels of the cheapest path from the pit at (x, y) to a strictly lower pixel, pit first;
    // empty when there is none within the radius.
    // to_edge: when there is none, the path to the cheapest reached cell on the window's edge.
    std::vector<int> find(const std::vector<float>& z, const std::vector<uint8_t>& fixed, int w, int h, int x, int y,
                          float margin, bool to_edge) {
        int fallback = -1;
        std::fill(cost_.begin(), cost_.end(), INFINITY);
        std::fill(done_.begin(), done_.end(), 0);
        using Entry = std::pair<float, int>;  // (cost, window cell); ties go to the lower cell index
        std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
        const int centre = radius_ * side_ + radius_;
        const float bottom = z[y * w + x];
        cost_[centre] = 0.0f;
        parent_[centre] = -1;
        open.push({0.0f, centre});
        while (!open.empty()) {
            const auto [d, cell] = open.top();
            open.pop();
            if (done_[cell]) continue;
            done_[cell] = 1;
            const int cx = cell % side_, cy = cell / side_;
            const int gx = x + cx - radius_, gy = y + cy - radius_;
            if (z[gy * w + gx] < bottom - margin) return trace(cell, w, x, y);
            if (fallback < 0 && z[gy * w + gx] < bottom) fallback = cell;
            if (cell != centre && fixed[gy * w + gx]) continue;  // may end a path, never carry one
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = cx + dx, ny = cy + dy, rx = gx + dx, ry = gy + dy;
                    if ((!dx && !dy) || nx < 0 || ny < 0 || nx >= side_ || ny >= side_ || rx < 0 || ry < 0 || rx >= w ||
                        ry >= h)
                        continue;
                    const int n = ny * side_ + nx;
                    if (done_[n]) continue;
                    const float step = std::max(0.0f, z[ry * w + rx] - bottom) + (dx && dy ? 1.414e-3f : 1e-3f);
                    if (d + step < cost_[n]) {
                        cost_[n] = d + step;
                        parent_[n] = cell;
                        open.push({cost_[n], n});
                    }
                }
        }
        if (fallback >= 0) return trace(fallback, w, x, y);
        return to_edge ? trace(cheapestEdgeCell(fixed, w, x, y), w, x, y) : std::vector<int>();
    }

private:
    // The reached, unprotected cell on the window's edge with the lowest path cost (ties: the lower
    // cell index); -1 when none was reached.
    int cheapestEdgeCell(const std::vector<uint8_t>& fixed, int w, int x, int y) const {
        int best = -1;
        for (int c = 0; c < cells_; ++c) {
            const int cx = c % side_, cy = c / side_;
            if (!done_[c] || (cx != 0 && cy != 0 && cx != side_ - 1 && cy != side_ - 1)) continue;
            if (fixed[(y + cy - radius_) * w + (x + cx - radius_)]) continue;  // never lowered
            if (best < 0 || cost_[c] < cost_[best]) best = c;
        }
        return best;
    }

    std::vector<int> trace(int cell, int w, int x, int y) const {
        if (cell < 0) return {};
        std::vector<int> path;
        for (; cell >= 0; cell = parent_[cell]) path.push_back((y + cell / side_ - radius_) * w + (x + cell % side_ - radius_));
        std::reverse(path.begin(), path.end());
        return path;
    }

    int radius_, side_, cells_;
    std::vector<float> cost_;
    std::vector<int> parent_;
    std::vector<uint8_t> done_;
};

bool copiedFromClosedDepression(const DatabaseLevel& db, const PixelState& s) {
    const size_t q = static_cast<size_t>(std::lround(s.y)) * db.width + static_cast<size_t>(std::lround(s.x));
    return q < db.closed.size() && db.closed[q];
}

// (height, row, column) order: of two equal heights the earlier pixel is the lower.
bool isPit(const std::vector<float>& z, int w, int c) {
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int n = c + dy * w + dx;
            if (n != c && (z[n] < z[c] || (z[n] == z[c] && n < c))) return false;
        }
    return true;
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

float DepthMargins::at(const ExemplarDatabase& db, int level) {
    if (margins_.size() != db.levels.size()) margins_.assign(db.levels.size(), 0.0f), known_.assign(db.levels.size(), 0);
    // No finer level follows level 0, so its paths need only reach the first lower pixel.
    if (!known_[level]) margins_[level] = level > 0 ? breachDepthMargin(db.levels[level]) : 0.0f, known_[level] = 1;
    return margins_[level];
}

BreachCounts breachPits(const DatabaseLevel& db, const LevelRegion& region, int radius, const DrainageInputs& inputs,
                        std::vector<PixelState>& state) {
    const int w = region.width, h = region.height;
    const std::vector<uint8_t> fixed = protectedPixels(db, inputs, state);
    std::vector<float> z(state.size());
    for (size_t i = 0; i < z.size(); ++i) z[i] = heightBilinear(db, state[i].x, state[i].y) + state[i].v;
    // Pits that can reach the needed pixels: within `radius` of them (interior pixels only).
    int x0 = 1, y0 = 1, x1 = w - 2, y1 = h - 2;
    if (inputs.needed.width > 0 && inputs.needed.height > 0) {
        x0 = std::max(x0, inputs.needed.x - region.x - radius), y0 = std::max(y0, inputs.needed.y - region.y - radius);
        x1 = std::min(x1, inputs.needed.x - region.x + inputs.needed.width - 1 + radius);
        y1 = std::min(y1, inputs.needed.y - region.y + inputs.needed.height - 1 + radius);
    }

    // Each worker searches every n-th row of pits into its own ceilings; the lowest carve wins.
    struct Worker {
        std::vector<float> ceiling;
        BreachCounts counts;
    };
    const int rows = std::max(0, y1 - y0 + 1);
    const int threads = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, std::min(4, std::max(1, rows / 8)));
    std::vector<Worker> workers(static_cast<size_t>(threads));
    auto work = [&](int t) {
        Worker& out = workers[static_cast<size_t>(t)];
        out.ceiling.assign(z.size(), INFINITY);
        PathSearch search(radius);
        for (int y = y0 + t; y <= y1; y += threads)
            for (int x = x0; x <= x1; ++x) {
                if (!isPit(z, w, y * w + x)) continue;
                ++out.counts.pits;
                if (copiedFromClosedDepression(db, state[y * w + x])) continue;  // a real basin: keep it
                const std::vector<int> path = search.find(z, fixed, w, h, x, y, inputs.depth_margin, inputs.carve_to_edge);
                if (path.empty()) continue;
                ++out.counts.breached;
                // A straight profile from the pit down to the lower pixel; cells already below it
                // stay. A path to the window's edge (carve_to_edge) ends below the pit.
                const float top = z[path.front()];
                const float bottom = z[path.back()] < top ? z[path.back()] : top - std::max(inputs.depth_margin, kEdgeDrop);
                const float k = static_cast<float>(path.size() - 1);
                for (size_t i = 0; i < path.size(); ++i) {
                    const float line = top - (top - bottom) * (static_cast<float>(i) / k);
                    out.ceiling[path[i]] = std::min(out.ceiling[path[i]], std::min(z[path[i]], line));
                }
            }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& t : pool) t.join();

    BreachCounts counts;
    std::vector<float>& ceiling = workers[0].ceiling;
    for (size_t t = 0; t < workers.size(); ++t) {
        counts.pits += workers[t].counts.pits, counts.breached += workers[t].counts.breached;
        if (t > 0)
            for (size_t i = 0; i < ceiling.size(); ++i) ceiling[i] = std::min(ceiling[i], workers[t].ceiling[i]);
    }
    for (size_t i = 0; i < z.size(); ++i) {
        if (ceiling[i] < z[i]) state[i].v = state[i].v - (z[i] - ceiling[i]);
        state[i].ceiling = ceiling[i];
    }
    return counts;
}

}  // namespace terrasynth::synth
