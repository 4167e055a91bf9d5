// Terrain-following by receding-horizon search over two-segment vertical-speed plans.
#include "terrasynth_game/autopilot.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace terrasynth::game {
namespace {

constexpr double kProfileStep = 100.0;  // metres between ground samples ahead
constexpr double kPlanStep = 0.25;      // seconds per simulated step of a plan
constexpr double kSegmentEnd[2] = {1.0, 3.0};  // a plan's three vertical speeds change at these times
constexpr double kSpeedStep = 25.0;     // m/s between candidate vertical speeds
// Plans are steered back beyond these shares of the band (below and above the target).
constexpr double kInnerBandBelow = 0.5, kInnerBandAbove = 0.8;

}  // namespace

std::vector<std::pair<double, double>> Autopilot::lookaheadPoints(const Aircraft& a) const {
    const double reach = s_.horizon_s * s_.horizontal_speed;
    const int n = static_cast<int>(std::ceil(reach / kProfileStep)) + 1;
    std::vector<std::pair<double, double>> points;
    points.reserve(static_cast<size_t>(n));
    const double ex = std::sin(s_.heading_rad), ey = std::cos(s_.heading_rad);
    for (int k = 0; k < n; ++k) points.emplace_back(a.x + ex * k * kProfileStep, a.y + ey * k * kProfileStep);
    return points;
}

std::optional<Guidance> Autopilot::decide(const Aircraft& a, const GroundQuery& ground) const {
    std::vector<double> profile;
    for (const auto& [x, y] : lookaheadPoints(a)) {
        const std::optional<GroundSample> g = ground(x, y);
        if (!g) return std::nullopt;
        profile.push_back(g->height_m);
    }
    const int steps = static_cast<int>(s_.horizon_s / kPlanStep);
    // Ground under the aircraft at every plan step.
    std::vector<double> ground_at(static_cast<size_t>(steps) + 1);
    for (int k = 0; k <= steps; ++k) {
        const double f = std::min(s_.horizontal_speed * k * kPlanStep / kProfileStep, double(profile.size() - 1));
        const size_t i = std::min(static_cast<size_t>(f), profile.size() - 2);
        ground_at[k] = profile[i] + (f - i) * (profile[i + 1] - profile[i]);
    }
    const double vz0 = a.speed * std::sin(a.pitch);
    const double dv = s_.max_vertical_accel * kPlanStep;
    // A plan holds one vertical speed per segment; its cost is the squared deviation from the target
    // height (nearer steps weigh more), a thousand times that beyond 80% of the band, a hundred
    // thousand beyond the band, a million within 20 m of the ground. `bound`: give up once the cost
    // exceeds the best so far.
    auto cost = [&](const double* command, double bound) {
        double z = a.z, vz = vz0, c = 0.01 * (command[0] - vz0) * (command[0] - vz0);
        int segment = 0;
        for (int k = 1; k <= steps && c < bound; ++k) {
            while (segment < 2 && k * kPlanStep > kSegmentEnd[segment]) ++segment;
            vz += std::clamp(command[segment] - vz, -dv, dv);
            z += vz * kPlanStep;
            const double agl = z - ground_at[k], dev = agl - s_.height_above_ground;
            c += dev * dev / (1.0 + 0.1 * k);
            // Erring high is safer than erring low: the inner band is narrower below the target.
            const double inner = dev < 0.0 ? -dev - kInnerBandBelow * s_.band : dev - kInnerBandAbove * s_.band;
            const double outside = std::fabs(dev) - s_.band;
            if (inner > 0.0) c += 1e3 * inner * inner;
            if (outside > 0.0) c += 1e5 * outside * outside;
            if (agl < 20.0) c += 1e6 * (20.0 - agl) * (20.0 - agl);
        }
        return c;
    };
    double best = std::numeric_limits<double>::max(), best_vz = vz0;
    const int n = static_cast<int>(2.0 * s_.max_vertical_speed / kSpeedStep) + 1;
    double command[3];
    for (int i = 0; i < n; ++i) {
        command[0] = -s_.max_vertical_speed + i * kSpeedStep;
        for (int j = 0; j < n; ++j) {
            command[1] = -s_.max_vertical_speed + j * kSpeedStep;
            for (int l = 0; l < n; ++l) {
                command[2] = -s_.max_vertical_speed + l * kSpeedStep;
                const double c = cost(command, best);
                if (c < best) {
                    best = c;
                    best_vz = command[0];
                }
            }
        }
    }
    Guidance g;
    g.heading = s_.heading_rad;
    g.horizontal_speed = s_.horizontal_speed;
    g.vertical_speed = best_vz;
    g.max_vertical_accel = s_.max_vertical_accel;
    return g;
}

}  // namespace terrasynth::game
