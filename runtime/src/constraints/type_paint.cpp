// Type painting and the freeze brush (terrasynth/constraints.h): round brush strokes stamped into a
// TypePaint, and the paint read back on other rectangles.
#include "constraints/type_paint.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace terrasynth {

std::vector<uint8_t> constraints::paintOnWindow(const TypePaint& paint, const PixelWindow& window, uint8_t outside) {
    std::vector<uint8_t> out(static_cast<size_t>(window.width) * window.height, outside);
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x) {
            const int64_t px = window.x + x - paint.x, py = window.y + y - paint.y;
            if (px >= 0 && py >= 0 && px < paint.width && py < paint.height)
                out[static_cast<size_t>(y) * window.width + x] = paint.types[static_cast<size_t>(py) * paint.width + px];
        }
    return out;
}

namespace {

// The dabs of a stroke: a round brush stamped along each segment at most max(0.5, r/2) pixels apart.
// Only the dabs within r of the paint's rectangle are visited (the others paint nothing), found by
// clipping each segment to the rectangle grown by r, so a stroke far outside it, or crossing it
// from 1e9 pixels away, costs what its part over the rectangle costs.
struct StrokeDabs {
    const TypePaint& paint;
    const std::vector<std::pair<double, double>>& line;
    double r;

    // Calls dab(x, y) (global pixels) for every dab that may touch the paint, in painting order;
    // returns how many there are. With `dab` null only counts, in O(segments).
    uint64_t visit(const std::function<void(double, double)>* dab) const {
        const double lo_x = static_cast<double>(paint.x) - r - 2.0, hi_x = static_cast<double>(paint.x) + paint.width + r + 2.0;
        const double lo_y = static_cast<double>(paint.y) - r - 2.0, hi_y = static_cast<double>(paint.y) + paint.height + r + 2.0;
        auto near = [&](double x, double y) { return x >= lo_x && x <= hi_x && y >= lo_y && y <= hi_y; };
        uint64_t count = 0;
        for (size_t i = 0; i < line.size(); ++i) {
            const double ax = line[i == 0 ? 0 : i - 1].first, ay = line[i == 0 ? 0 : i - 1].second;
            if (i == 0) {
                if (near(ax, ay)) ++count, dab ? (*dab)(ax, ay) : void();
                continue;
            }
            const double dx = line[i].first - ax, dy = line[i].second - ay;
            const int64_t steps = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(std::hypot(dx, dy) / std::max(0.5, r * 0.5))));
            // Liang-Barsky: the parameter range of the segment inside the grown rectangle.
            double t0 = 0.0, t1 = 1.0;
            auto clip = [&](double p, double q) {  // keep t where p * t <= q
                if (p == 0.0) return q >= 0.0;
                const double t = q / p;
                if (p < 0.0) t0 = std::max(t0, t);
                else t1 = std::min(t1, t);
                return t0 <= t1;
            };
            if (!(clip(-dx, ax - lo_x) && clip(dx, hi_x - ax) && clip(-dy, ay - lo_y) && clip(dy, hi_y - ay))) continue;
            const int64_t first = std::max<int64_t>(1, static_cast<int64_t>(std::floor(t0 * steps)) - 1);
            const int64_t last = std::min<int64_t>(steps, static_cast<int64_t>(std::ceil(t1 * steps)) + 1);
            if (!dab) {
                count += static_cast<uint64_t>(std::max<int64_t>(0, last - first + 1));
                continue;
            }
            for (int64_t k = first; k <= last; ++k) {
                // The same arithmetic as stamping every step from the segment's start.
                const double x = ax + dx * static_cast<double>(k) / static_cast<double>(steps);
                const double y = ay + dy * static_cast<double>(k) / static_cast<double>(steps);
                if (near(x, y)) ++count, (*dab)(x, y);
            }
        }
        return count;
    }
};

// Pixels (x, y) of the paint with (x - cx)^2 + (y - cy)^2 <= r^2 on row y: an interval around cx,
// estimated with a square root and settled with that exact test.
bool rowSpan(int y, double cx, double cy, double r, int width, int* from, int* to) {
    auto in = [&](int x) { return (x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r; };
    const double half = std::sqrt(std::max(0.0, r * r - (y - cy) * (y - cy)));
    const int x0 = static_cast<int>(std::max(0.0, std::floor(cx - r)));
    const int x1 = static_cast<int>(std::min(width - 1.0, std::ceil(cx + r)));
    if (x0 > x1) return false;
    int a = static_cast<int>(std::clamp(std::ceil(cx - half), double(x0), double(x1)));
    int b = static_cast<int>(std::clamp(std::floor(cx + half), double(x0), double(x1)));
    while (a > x0 && in(a - 1)) --a;
    while (a <= x1 && !in(a)) ++a;
    while (b < x1 && in(b + 1)) ++b;
    while (b >= x0 && !in(b)) --b;
    if (a > b) return false;
    *from = a, *to = b;
    return true;
}

}  // namespace

uint64_t strokePaintCost(const TypePaint& paint, const std::vector<std::pair<double, double>>& line, double radius_px) {
    if (paint.width <= 0 || paint.height <= 0) return 0;
    const uint64_t dabs = StrokeDabs{paint, line, radius_px}.visit(nullptr);
    const uint64_t rows = static_cast<uint64_t>(std::min(2.0 * radius_px + 3.0, static_cast<double>(paint.height)));
    return dabs * rows + static_cast<uint64_t>(paint.width) * paint.height;
}

void paintStroke(TypePaint& paint, const std::vector<std::pair<double, double>>& line, double radius_px, uint8_t value) {
    if (paint.width <= 0 || paint.height <= 0 || !(radius_px > 0.0)) return;
    const double r = radius_px;
    // Every dab gives one span per row it covers; the stroke paints the union of its dabs with one
    // value, so the spans of each row are merged and filled once.
    std::vector<std::vector<std::pair<int, int>>> rows(static_cast<size_t>(paint.height));
    const std::function<void(double, double)> dab = [&](double gx, double gy) {
        const double cx = gx - static_cast<double>(paint.x), cy = gy - static_cast<double>(paint.y);
        const int y0 = static_cast<int>(std::max(0.0, std::floor(cy - r)));
        const int y1 = static_cast<int>(std::min(paint.height - 1.0, std::ceil(cy + r)));
        for (int y = y0; y <= y1; ++y) {
            int from = 0, to = 0;
            if (rowSpan(y, cx, cy, r, paint.width, &from, &to)) rows[static_cast<size_t>(y)].push_back({from, to});
        }
    };
    StrokeDabs{paint, line, r}.visit(&dab);
    for (int y = 0; y < paint.height; ++y) {
        std::vector<std::pair<int, int>>& spans = rows[static_cast<size_t>(y)];
        if (spans.empty()) continue;
        std::sort(spans.begin(), spans.end());
        uint8_t* row = &paint.types[static_cast<size_t>(y) * paint.width];
        int filled = -1;  // pixels up to here are painted already
        for (const auto& [from, to] : spans) {
            for (int x = std::max(from, filled + 1); x <= to; ++x) row[x] = value;
            filled = std::max(filled, to);
        }
    }
}

}  // namespace terrasynth
