// terrasynth_game/autopilot.h: terrain-following guidance (for --autopilot and benchmarks).
//
// Holds a course and a horizontal speed and keeps the aircraft a set height above the exact ground
// by receding-horizon control: every step it solves a dynamic programme over vertical-speed plans
// (the speed changes by at most the acceleration limit every 0.25 s, exactly as the flight model's
// guided mode integrates it) against the ground profile ahead (every 10 m up to horizon_s of
// flight, from GroundCache; each plan step sees the highest and lowest ground it passes over), and
// applies the best plan's first command. The score is the squared deviation from the target
// height, heavy penalties for straying far from it (sooner below than above: erring high is safer),
// far heavier ones for leaving [target - band, target + band] (plans keep 3 m inside it) and for
// the ground itself. Deterministic: the same state and ground give the same command. About 1.2 ms
// (2-core machine, default settings).
// The vertical acceleration (80 m/s^2, 8 g, by default) is an arcade figure: on 92.6 m terrain at
// 300 m/s, crossing sharp ridges within +-100 m needs that agility. On the seed-42 test flight the
// narrowest corridor any 60 m/s^2 trajectory can keep is +-95 m (exhaustive search over the flown
// profile), so the band held with only a metre to spare; at 80 m/s^2 the flight stays in 212-392 m.
#pragma once

#include <optional>
#include <vector>

#include "terrasynth_game/flight_model.h"

namespace terrasynth::game {

struct AutopilotSettings {
    double heading_rad = 0.0;
    double horizontal_speed = 300.0;   // m/s
    double height_above_ground = 300.0;
    double band = 100.0;               // the plan is penalised outside target +- band
    double horizon_s = 8.0;            // seconds of flight looked ahead
    double max_vertical_accel = 80.0;  // m/s^2
    double max_vertical_speed = 250.0; // m/s
};

class Autopilot {
public:
    explicit Autopilot(const AutopilotSettings& s) : s_(s) {}
    const AutopilotSettings& settings() const { return s_; }

    // The world points (x, y) whose ground the next decision reads, from the aircraft onwards.
    std::vector<std::pair<double, double>> lookaheadPoints(const Aircraft& a) const;
    // The guidance for this step; nullopt when a lookahead point has no ground yet.
    std::optional<Guidance> decide(const Aircraft& a, const GroundQuery& ground) const;

private:
    // Cost of one plan state at step `step`: its lowest, centre and highest height above the ground
    // during the step (m).
    double stepCost(double lowest, double centre, double highest, int step) const;

    AutopilotSettings s_;
};

}  // namespace terrasynth::game
