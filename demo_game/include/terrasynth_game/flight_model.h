// terrasynth_game/flight_model.h: the aircraft and a falling body, and how they meet the ground.
//
// An arcade flight model (the nose is the velocity's direction; roll turns it, as in a coordinated
// turn; thrust, drag and gravity along the path set the speed; below the stall speed the nose drops)
// integrated in fixed sub-steps, so the same inputs and steps give the same bits. The ground is
// whatever `GroundQuery` answers (the game passes GroundCache: exact heights); a step where it has
// no answer skips collision for that sub-step (only real-time play ever lets that happen).
// Contact: hitting the ground faster than crash_speed (along the ground's normal) is a crash;
// slower, the aircraft slides along the surface with friction, never below it.
// World frame of terrasynth/grid.h: x east, y north, z up, metres. Plain data; thread-compatible.
#pragma once

#include <functional>
#include <optional>

#include "terrasynth_game/exact_ground.h"

namespace terrasynth::game {

using GroundQuery = std::function<std::optional<GroundSample>(double wx, double wy)>;

struct Controls {
    double pitch = 0.0;     // [-1, 1]: +1 nose up (S), -1 nose down (W)
    double roll = 0.0;      // [-1, 1]: +1 right wing down (D), -1 left (A)
    double yaw = 0.0;       // [-1, 1]: +1 nose right (E), -1 left (Q)
    double throttle = 0.0;  // [-1, 1]: change per second, +1 Shift (more), -1 Ctrl (less)
};

struct Aircraft {
    double x = 0.0, y = 0.0, z = 0.0;  // metres
    double speed = 0.0;                 // along the nose, m/s
    double heading = 0.0;               // radians clockwise from north
    double pitch = 0.0;                 // radians, nose up positive, in [-1.4, 1.4]
    double roll = 0.0;                  // radians, right wing down positive, in [-1.4, 1.4]
    double throttle = 0.55;             // [0, 1]
    bool on_ground = false;             // sliding on the ground after the last step

    // Velocity (m/s) along the nose.
    void velocity(double* vx, double* vy, double* vz) const;
};

struct FlightParams {
    double gravity = 9.81;
    double max_thrust = 30.0;     // m/s^2 at full throttle
    double top_speed = 420.0;     // level flight at full throttle (sets the drag)
    double stall_speed = 70.0;
    double pitch_rate = 1.0, roll_rate = 1.8, yaw_rate = 0.35;  // rad/s at full deflection
    double crash_speed = 12.0;    // m/s into the ground (along its normal) that wrecks the aircraft
    double gear_height = 1.5;     // the aircraft's reference point rests this far above the surface
    double ground_friction = 0.35;  // sliding: deceleration = friction * g
    double substep = 1.0 / 120.0;   // integration step, seconds
};

enum class StepOutcome { Airborne, Sliding, Crashed };

// Advances the aircraft by dt seconds under pilot controls (integer number of sub-steps; the
// remainder is integrated as a shorter last step). Stops at a crash, leaving the aircraft where it
// hit; the caller respawns it.
StepOutcome stepAircraft(Aircraft& a, const Controls& c, double dt, const GroundQuery& ground,
                         const FlightParams& p = {});

// What the autopilot asks for: a course, a speed and a vertical speed, reached within the given
// accelerations (the autopilot is a guidance law, not a pilot: see autopilot.h).
struct Guidance {
    double heading = 0.0;          // radians clockwise from north
    double horizontal_speed = 300.0;  // m/s
    double vertical_speed = 0.0;   // m/s, up positive
    double max_vertical_accel = 40.0;  // m/s^2
};
StepOutcome stepGuided(Aircraft& a, const Guidance& g, double dt, const GroundQuery& ground,
                       const FlightParams& p = {});

// A body falling under gravity and air drag, coming to rest on the ground (the drop test).
struct Body {
    double x = 0.0, y = 0.0, z = 0.0;
    double vx = 0.0, vy = 0.0, vz = 0.0;
    bool in_contact = false;
    bool at_rest = false;  // in contact, still, and the slope's pull within static friction
};
struct BodyParams {
    double gravity = 9.81;
    double drag = 0.003;     // 1/m: deceleration = drag * speed^2 (terminal speed sqrt(g / drag) = 57 m/s)
    double friction = 0.8;   // Coulomb coefficient, static and sliding
    double rest_speed = 0.05;
    double substep = 1.0 / 120.0;
};
void stepBody(Body& b, double dt, const GroundQuery& ground, const BodyParams& p = {});

}  // namespace terrasynth::game
