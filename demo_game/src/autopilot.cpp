// Terrain-following by receding-horizon dynamic programming over vertical-speed plans.
#include "terrasynth_game/autopilot.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace terrasynth::game {
namespace {

// Metres between ground samples ahead: a ninth of the 92.6 m grid. Sparser samples cut the crests
// (100 m missed 16 m of a ridge top on the default terrain and the aircraft dipped below the band).
constexpr double kProfileStep = 10.0;
constexpr double kPlanStep = 0.25;  // seconds per step of a plan
// Plans are steered back beyond these shares of the band (below and above the target).
constexpr double kInnerBandBelow = 0.5, kInnerBandAbove = 0.8;
// Plans keep this far inside the band, for what the plan does not model (the ground between profile
// samples, the flight model's sub-steps).
constexpr double kBandSafety = 3.0;
// Heights considered per plan step: this far beyond the band either side (farther is never better).
constexpr double kBeyondBand = 150.0;
constexpr double kUnreachable = 1e30;

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

double Autopilot::stepCost(double lowest, double centre, double highest, int step) const {
    if (lowest < 0.0) return kUnreachable;  // into the ground
    const double dev = centre - s_.height_above_ground;
    double c = dev * dev / (1.0 + 0.1 * step);
    // Erring high is safer than erring low: the inner band is narrower below the target.
    const double below = s_.height_above_ground - lowest, above = highest - s_.height_above_ground;
    const double inner = std::max(below - kInnerBandBelow * s_.band, above - kInnerBandAbove * s_.band);
    const double outside = std::max(below, above) - (s_.band - kBandSafety);
    if (inner > 0.0) c += 1e3 * inner * inner;
    // Leaving the band outweighs any deviation inside it: plans stay in whenever the ground allows.
    if (outside > 0.0) c += 1e9 * outside * outside;
    if (lowest < 20.0) c += 1e6 * (20.0 - lowest) * (20.0 - lowest);
    return c;
}

std::optional<Guidance> Autopilot::decide(const Aircraft& a, const GroundQuery& ground) const {
    std::vector<double> profile;
    for (const auto& [x, y] : lookaheadPoints(a)) {
        const std::optional<GroundSample> g = ground(x, y);
        if (!g) return std::nullopt;
        profile.push_back(g->height_m);
    }
    // State after k plan steps: vertical speed vz0 + j * dv and height z0 + k * vz0 * dt + m * dz.
    // Each step changes j by -1, 0 or +1 (the acceleration limit) and m by the old j plus the new
    // (the mean speed over the step, as the flight model integrates it), so with dz = dv * dt / 2 the
    // states lie exactly on this grid and no interpolation blurs the plan.
    const int steps = static_cast<int>(s_.horizon_s / kPlanStep);
    const double vz0 = a.speed * std::sin(a.pitch);
    const double dv = s_.max_vertical_accel * kPlanStep, dz = 0.5 * dv * kPlanStep;
    const int j_lo = static_cast<int>(std::ceil((-s_.max_vertical_speed - vz0) / dv));
    const int j_hi = static_cast<int>(std::floor((s_.max_vertical_speed - vz0) / dv));
    if (j_lo > j_hi) return std::nullopt;  // a vertical speed the limits cannot hold (not from guidance)
    const int nj = j_hi - j_lo + 1;

    // The ground a state at step k with speed index j flies over: the profile samples within half a
    // step either side, each seen from the height the aircraft has there at that speed. Highest and
    // lowest of (ground - height change) bound the clearance over the whole step, so a crest between
    // two steps counts; the centre (interpolated) scores the deviation.
    const double samples_per_step = s_.horizontal_speed * kPlanStep / kProfileStep;
    const int last = static_cast<int>(profile.size()) - 1;
    const size_t cells = static_cast<size_t>(steps + 1) * nj;
    std::vector<double> ground_high(cells), ground_low(cells), ground_centre(static_cast<size_t>(steps) + 1);
    for (int k = 0; k <= steps; ++k) {
        const double c = std::min(k * samples_per_step, static_cast<double>(last));
        const int lo = std::clamp(static_cast<int>(std::floor(c - 0.5 * samples_per_step)), 0, last);
        const int hi = std::clamp(static_cast<int>(std::ceil(c + 0.5 * samples_per_step)), lo, last);
        const int i = std::min(static_cast<int>(c), last - 1);
        ground_centre[k] = profile[i] + (c - i) * (profile[i + 1] - profile[i]);
        for (int j = 0; j < nj; ++j) {
            const double vz = vz0 + (j + j_lo) * dv;
            double high = -std::numeric_limits<double>::infinity(), low = std::numeric_limits<double>::infinity();
            for (int s = lo; s <= hi; ++s) {
                const double seen = profile[s] - vz * (s - c) * kProfileStep / s_.horizontal_speed;
                high = std::max(high, seen), low = std::min(low, seen);
            }
            ground_high[static_cast<size_t>(k) * nj + j] = high;
            ground_low[static_cast<size_t>(k) * nj + j] = low;
        }
    }
    auto heightAt = [&](int k, int m) { return a.z + k * vz0 * kPlanStep + m * dz; };
    auto cost = [&](int k, int m, int j) {
        const double z = heightAt(k, m);
        const size_t cell = static_cast<size_t>(k) * nj + j;
        return stepCost(z - ground_high[cell], z - ground_centre[k], z - ground_low[cell], k);
    };
    // Heights considered at step k, as grid rows m: the band around the centre ground and a margin.
    auto rowRange = [&](int k) {
        const double base = a.z + k * vz0 * kPlanStep, target = ground_centre[k] + s_.height_above_ground;
        return std::make_pair(static_cast<int>(std::floor((target - s_.band - kBeyondBand - base) / dz)),
                              static_cast<int>(std::ceil((target + s_.band + kBeyondBand - base) / dz)));
    };

    // Backward pass: cost-to-go of every state at step k, from the one at step k + 1. Speed indices
    // are stored offset by -j_lo (0..nj-1).
    std::vector<double> next, here;
    std::pair<int, int> next_rows = rowRange(steps);
    next.assign(static_cast<size_t>(next_rows.second - next_rows.first + 1) * nj, 0.0);
    for (int m = next_rows.first; m <= next_rows.second; ++m)
        for (int j = 0; j < nj; ++j) next[static_cast<size_t>(m - next_rows.first) * nj + j] = cost(steps, m, j);
    auto costToGo = [&](const std::vector<double>& layer, std::pair<int, int> rows, int m, int j) {
        if (j < 0 || j >= nj || m < rows.first || m > rows.second) return kUnreachable;
        return layer[static_cast<size_t>(m - rows.first) * nj + j];
    };
    for (int k = steps - 1; k >= 1; --k) {
        const std::pair<int, int> rows = rowRange(k);
        here.assign(static_cast<size_t>(rows.second - rows.first + 1) * nj, kUnreachable);
        for (int m = rows.first; m <= rows.second; ++m) {
            for (int j = 0; j < nj; ++j) {
                const double c = cost(k, m, j);
                if (c >= kUnreachable) continue;
                double best = kUnreachable;
                for (int d = -1; d <= 1; ++d) {
                    const int jn = j + d;
                    best = std::min(best, costToGo(next, next_rows, m + j + jn + 2 * j_lo, jn) + (d != 0 ? 1.0 : 0.0));
                }
                here[static_cast<size_t>(m - rows.first) * nj + j] = c + best;
            }
        }
        next.swap(here);
        next_rows = rows;
    }
    // The first step from the aircraft's state (m = 0, speed vz0, index -j_lo); ties keep the gentler
    // change, so the same state and ground give the same command.
    double best = kUnreachable;
    int best_d = 0;
    for (int d : {0, -1, 1}) {
        const double c = costToGo(next, next_rows, d, -j_lo + d) + (d != 0 ? 1.0 : 0.0);
        if (c < best) best = c, best_d = d;
    }
    Guidance g;
    g.heading = s_.heading_rad;
    g.horizontal_speed = s_.horizontal_speed;
    g.vertical_speed = std::clamp(vz0 + best_d * dv, -s_.max_vertical_speed, s_.max_vertical_speed);
    g.max_vertical_accel = s_.max_vertical_accel;
    return g;
}

}  // namespace terrasynth::game
