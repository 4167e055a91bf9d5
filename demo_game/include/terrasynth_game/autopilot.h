// terrasynth_game/autopilot.h: terrain-following guidance (for --autopilot and benchmarks).
//
// Holds a course and a horizontal speed and keeps the aircraft a set height above the exact ground
// by receding-horizon control: every step it scores vertical-speed plans (three vertical speeds:
// for the next second, until 3 s, and after; 25 m/s apart) over the ground profile ahead (every
// 100 m up to horizon_s of flight, from GroundCache) with the vertical acceleration limit of the
// flight model's guided mode, and applies the best plan's first command. The score is the squared
// deviation from the target height, heavy penalties for straying far from it (sooner below than
// above: erring high is safer) and for leaving [target - band, target + band], heavier ones for
// the ground itself. Deterministic: the same state and ground give the same command. About 1 ms.
// The vertical acceleration (60 m/s^2, 6 g, by default) is an arcade figure: on 92.6 m terrain at
// 300 m/s, crossing sharp ridges within +-100 m needs that agility (at 40 m/s^2 the seed-42 test
// flight dips to 185 m).
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
    double horizon_s = 6.0;           // seconds of flight looked ahead
    double max_vertical_accel = 60.0;  // m/s^2
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
    AutopilotSettings s_;
};

}  // namespace terrasynth::game
