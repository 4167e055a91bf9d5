// Area-of-effect envelope of a curve constraint with isocurve smoothing (Gain et al. 2015 s5.1,
// Figure 5: "an isocurve extraction followed by smoothing the area of effect envelope").
//
// The closest-point parameter t(p) jumps across the medial axis on the concave side of the course,
// so the envelope d(p) < reach(t(p)) has steps there (Figure 5a). We extract the envelope as the
// f = 0 isocurve, smooth only the contour around those jumps and fill the smoothed loops.
#include "constraints/curve_envelope.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace terrasynth::constraints {
namespace {

constexpr float kOutside = 1.0f;  // f of the closing ring and of pixels without a distance

struct Contour {
    std::vector<double> x, y;        // per vertex, global level pixels
    std::vector<uint8_t> jump;       // the vertex's grid edge straddles a parametrisation jump
    std::vector<int> next_a, next_b; // the two neighbours of each vertex
};

// The grid padded by one outside ring so that every isocurve closes into a loop.
class PaddedGrid {
public:
    explicit PaddedGrid(const EnvelopeGrid& g) : g_(g), width(g.width + 2), height(g.height + 2) {}
    float f(int px, int py) const {
        if (!interior(px, py)) return kOutside;
        const float v = g_.f[index(px, py)];
        return std::isfinite(v) ? v : kOutside;
    }
    bool known(int px, int py) const { return interior(px, py) && std::isfinite(g_.f[index(px, py)]); }
    double s(int px, int py) const { return g_.s[index(px, py)]; }
    double globalX(double px) const { return g_.x0 + px - 1.0; }
    double globalY(double py) const { return g_.y0 + py - 1.0; }

    const EnvelopeGrid& g_;
    const int width, height;

private:
    bool interior(int px, int py) const { return px >= 1 && py >= 1 && px <= g_.width && py <= g_.height; }
    size_t index(int px, int py) const { return static_cast<size_t>(py - 1) * g_.width + (px - 1); }
};

// Marching squares over the padded grid; vertices live on grid edges (id 2*cell or 2*cell + 1 for the
// horizontal or vertical edge leaving pixel `cell` east or south).
Contour extractContour(const PaddedGrid& grid, double jump_arc_px) {
    Contour c;
    std::vector<int> vertex_of(2 * static_cast<size_t>(grid.width) * grid.height, -1);
    auto vertex = [&](int ax, int ay, bool horizontal) {
        const size_t id = 2 * (static_cast<size_t>(ay) * grid.width + ax) + (horizontal ? 0 : 1);
        if (vertex_of[id] >= 0) return vertex_of[id];
        const int bx = ax + (horizontal ? 1 : 0), by = ay + (horizontal ? 0 : 1);
        const double fa = grid.f(ax, ay), fb = grid.f(bx, by);
        // Never exactly on a pixel centre, so the fill classifies f = 0 pixels as outside like f < 0 does.
        const double w = std::clamp(fa / (fa - fb), 1e-6, 1.0 - 1e-6);
        c.x.push_back(grid.globalX(ax + (horizontal ? w : 0.0)));
        c.y.push_back(grid.globalY(ay + (horizontal ? 0.0 : w)));
        c.jump.push_back(grid.known(ax, ay) && grid.known(bx, by) && std::abs(grid.s(ax, ay) - grid.s(bx, by)) > jump_arc_px);
        c.next_a.push_back(-1);
        c.next_b.push_back(-1);
        return vertex_of[id] = static_cast<int>(c.x.size() - 1);
    };
    auto connect = [&](int a, int b) {
        (c.next_a[a] < 0 ? c.next_a[a] : c.next_b[a]) = b;
        (c.next_a[b] < 0 ? c.next_a[b] : c.next_b[b]) = a;
    };
    for (int cy = 0; cy + 1 < grid.height; ++cy)
        for (int cx = 0; cx + 1 < grid.width; ++cx) {
            const float f0 = grid.f(cx, cy), f1 = grid.f(cx + 1, cy), f2 = grid.f(cx + 1, cy + 1), f3 = grid.f(cx, cy + 1);
            const bool in0 = f0 < 0, in1 = f1 < 0, in2 = f2 < 0, in3 = f3 < 0;
            if (in0 == in1 && in1 == in2 && in2 == in3) continue;
            int crossing[4], n = 0;  // top, right, bottom, left edges that change sign
            if (in0 != in1) crossing[n++] = vertex(cx, cy, true);
            if (in1 != in2) crossing[n++] = vertex(cx + 1, cy, false);
            if (in3 != in2) crossing[n++] = vertex(cx, cy + 1, true);
            if (in0 != in3) crossing[n++] = vertex(cx, cy, false);
            if (n == 2) {
                connect(crossing[0], crossing[1]);
            } else {
                // Saddle: the sign at the centre (mean of the corners) decides which diagonal joins.
                const bool centre_in = (f0 + f1 + f2 + f3) < 0;
                if (centre_in == in0) {
                    connect(crossing[0], crossing[1]);  // cut off corners 1 and 3
                    connect(crossing[2], crossing[3]);
                } else {
                    connect(crossing[3], crossing[0]);  // cut off corners 0 and 2
                    connect(crossing[1], crossing[2]);
                }
            }
        }
    return c;
}

std::vector<std::vector<int>> loopsOf(const Contour& c) {
    std::vector<std::vector<int>> loops;
    std::vector<uint8_t> seen(c.x.size(), 0);
    for (size_t start = 0; start < c.x.size(); ++start) {
        if (seen[start]) continue;
        std::vector<int> loop;
        int prev = -1, cur = static_cast<int>(start);
        while (cur >= 0 && !seen[cur]) {
            seen[cur] = 1;
            loop.push_back(cur);
            const int next = c.next_a[cur] != prev ? c.next_a[cur] : c.next_b[cur];
            prev = cur;
            cur = next;
        }
        loops.push_back(std::move(loop));
    }
    return loops;
}

double smoothstep(double a) {
    a = std::clamp(a, 0.0, 1.0);
    return a * a * (3.0 - 2.0 * a);
}

int smoothingIterations(const EnvelopeSmoothing& s) { return std::max(1, s.window * s.window / 2); }

// Laplacian smoothing of the loop stretches near jumps, weighted 1 at a jump and falling to 0 over
// `window` vertices, so the step of Figure 5a becomes a ramp and the rest of the envelope is exact.
void smoothNearJumps(Contour& c, const std::vector<int>& loop, const EnvelopeSmoothing& smoothing) {
    const int n = static_cast<int>(loop.size());
    if (n < 4) return;
    // Index distance to the nearest jump vertex around the loop (two sweeps each way).
    std::vector<int> dist(n, std::numeric_limits<int>::max() / 2);
    for (int i = 0; i < n; ++i)
        if (c.jump[loop[i]]) dist[i] = 0;
    for (int sweep = 0; sweep < 2; ++sweep) {
        for (int i = 0; i < 2 * n; ++i) dist[(i + 1) % n] = std::min(dist[(i + 1) % n], dist[i % n] + 1);
        for (int i = 2 * n; i > 0; --i) dist[(i - 1) % n] = std::min(dist[(i - 1) % n], dist[i % n] + 1);
    }
    std::vector<int> active;
    std::vector<double> weight;
    for (int i = 0; i < n; ++i) {
        const double w = 1.0 - smoothstep(double(dist[i]) / smoothing.window);
        if (w <= 0.0) continue;
        active.push_back(i);
        weight.push_back(0.5 * w);
    }
    if (active.empty()) return;
    std::vector<double> x(n), y(n);
    for (int i = 0; i < n; ++i) {
        x[i] = c.x[loop[i]];
        y[i] = c.y[loop[i]];
    }
    std::vector<double> nx(active.size()), ny(active.size());
    for (int it = smoothingIterations(smoothing); it > 0; --it) {
        for (size_t k = 0; k < active.size(); ++k) {
            const int i = active[k], a = (i + n - 1) % n, b = (i + 1) % n;
            nx[k] = x[i] + weight[k] * (0.5 * (x[a] + x[b]) - x[i]);
            ny[k] = y[i] + weight[k] * (0.5 * (y[a] + y[b]) - y[i]);
        }
        for (size_t k = 0; k < active.size(); ++k) {
            x[active[k]] = nx[k];
            y[active[k]] = ny[k];
        }
    }
    for (int i = 0; i < n; ++i) {
        c.x[loop[i]] = x[i];
        c.y[loop[i]] = y[i];
    }
}

// Even-odd fill of the loops at the grid's pixel centres (half-open in y so shared vertices count once).
std::vector<uint8_t> fillLoops(const Contour& c, const std::vector<std::vector<int>>& loops, const EnvelopeGrid& g) {
    std::vector<std::vector<double>> rows(static_cast<size_t>(g.height));
    for (const std::vector<int>& loop : loops) {
        const size_t n = loop.size();
        for (size_t i = 0; i < n; ++i) {
            int p = loop[i], q = loop[(i + 1) % n];
            if (c.y[p] == c.y[q]) continue;
            if (c.y[p] > c.y[q]) std::swap(p, q);
            const int first = std::max(static_cast<int>(std::ceil(c.y[p])), g.y0);
            const int last = std::min(static_cast<int>(std::ceil(c.y[q])) - 1, g.y0 + g.height - 1);
            const double slope = (c.x[q] - c.x[p]) / (c.y[q] - c.y[p]);
            for (int row = first; row <= last; ++row) rows[row - g.y0].push_back(c.x[p] + (row - c.y[p]) * slope);
        }
    }
    std::vector<uint8_t> mask(static_cast<size_t>(g.width) * g.height, 0);
    for (int r = 0; r < g.height; ++r) {
        std::vector<double>& xs = rows[r];
        std::sort(xs.begin(), xs.end());
        for (size_t k = 0; k + 1 < xs.size(); k += 2) {
            const int from = std::max(static_cast<int>(std::ceil(xs[k])), g.x0);
            const int to = std::min(static_cast<int>(std::ceil(xs[k + 1])) - 1, g.x0 + g.width - 1);
            for (int x = from; x <= to; ++x) mask[static_cast<size_t>(r) * g.width + (x - g.x0)] = 1;
        }
    }
    return mask;
}

}  // namespace

int envelopeInfluencePx(const EnvelopeSmoothing& smoothing) {
    if (!smoothing.enabled) return 0;
    // A vertex moves only under vertices within `iterations` steps along its active stretch, and
    // marching-squares vertices are at most sqrt(2) pixels apart.
    return static_cast<int>(std::ceil(1.5 * (smoothingIterations(smoothing) + smoothing.window + 2)));
}

std::vector<uint8_t> envelopeMask(const EnvelopeGrid& grid, const EnvelopeSmoothing& smoothing) {
    if (!smoothing.enabled) {
        std::vector<uint8_t> mask(grid.f.size());
        for (size_t i = 0; i < mask.size(); ++i) mask[i] = grid.f[i] < 0.0f ? 1 : 0;
        return mask;
    }
    const PaddedGrid padded(grid);
    Contour contour = extractContour(padded, smoothing.jump_arc_px);
    const std::vector<std::vector<int>> loops = loopsOf(contour);
    for (const std::vector<int>& loop : loops) smoothNearJumps(contour, loop, smoothing);
    return fillLoops(contour, loops, grid);
}

}  // namespace terrasynth::constraints
