// D8 drainage area (O'Callaghan & Mark 1984) on the Priority-Flood+epsilon filled surface.
//
// Filling in double precision makes every interior cell strictly higher than one neighbour, so the
// steepest-descent receivers form a forest rooted at border cells; areas are then pushed downstream
// in topological order (sources first), which is O(n) with no sort.
#include <cmath>
#include <cstdint>

#include "stats/field_check.h"
#include "stats/flow_routing.h"
#include "stats/priority_flood.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {

namespace {

// Receiver of each cell (index of the steepest lower neighbour), -1 when it drains off the field.
// Border cells always drain off the field: what lies beyond is unknown, and routing them along the
// border would invent a channel that collects the whole edge into the lowest corner.
std::vector<int32_t> steepestDescentReceivers(const std::vector<double>& z, int w, int h, double lx, double ly) {
    static const int kDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
    static const int kDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
    double inv_dist[8];
    for (int k = 0; k < 8; ++k) inv_dist[k] = 1.0 / std::hypot(kDx[k] * lx, kDy[k] * ly);
    std::vector<int32_t> receiver(z.size(), -1);
    for (int y = 1; y < h - 1; ++y)
        for (int x = 1; x < w - 1; ++x) {
            const int32_t c = y * w + x;
            double best = 0.0;
            for (int k = 0; k < 8; ++k) {
                const int32_t n = (y + kDy[k]) * w + x + kDx[k];
                const double gradient = (z[c] - z[n]) * inv_dist[k];
                if (gradient > best) {
                    best = gradient;
                    receiver[c] = n;
                }
            }
        }
    return receiver;
}

}  // namespace

namespace stats {

bool inDepression(float original, double filled) {
    const double half_step = 0.5 * (std::nextafter(std::fabs(original), INFINITY) - std::fabs(original));
    return filled - static_cast<double>(original) > half_step;
}

FlowRouting routeFlow(const Heightfield& field) {
    requireField(field);
    const int w = field.width, h = field.height;
    FlowRouting flow;
    flow.filled.assign(field.heights.begin(), field.heights.end());
    priorityFlood(flow.filled, w, h, /*epsilon=*/true);
    const std::vector<int32_t> receiver =
        steepestDescentReceivers(flow.filled, w, h, field.meters_per_pixel_x, field.meters_per_pixel_y);

    std::vector<int32_t> donors(field.size(), 0);
    for (int32_t r : receiver)
        if (r >= 0) ++donors[r];
    std::vector<int32_t> ready;
    ready.reserve(field.size());
    for (size_t i = 0; i < field.size(); ++i)
        if (donors[i] == 0) ready.push_back(static_cast<int32_t>(i));

    flow.area.assign(field.size(), field.meters_per_pixel_x * field.meters_per_pixel_y);
    for (size_t next = 0; next < ready.size(); ++next) {
        const int32_t c = ready[next];
        const int32_t r = receiver[c];
        if (r < 0) continue;
        flow.area[r] += flow.area[c];
        if (--donors[r] == 0) ready.push_back(r);
    }
    return flow;
}

}  // namespace stats

std::vector<double> drainageArea(const Heightfield& field) { return stats::routeFlow(field).area; }

}  // namespace terrasynth
