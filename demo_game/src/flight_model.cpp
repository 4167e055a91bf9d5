// The arcade flight model, the autopilot's guided flight, and a falling body: fixed sub-steps, and
// contact with the exact ground.
#include "terrasynth_game/flight_model.h"

#include <algorithm>
#include <cmath>

namespace terrasynth::game {
namespace {

constexpr double kMaxAttitude = 1.4;  // radians of pitch and roll

// Calls step(h) for sub-steps covering dt: whole sub-steps, then the remainder.
template <class Step>
bool forSubsteps(double dt, double substep, Step&& step) {
    double done = 0.0;
    while (done < dt - 1e-12) {
        const double h = std::min(substep, dt - done);
        if (!step(h)) return false;
        done += h;
    }
    return true;
}

double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The aircraft against the ground after it moved: above the surface it flies; touching it slower
// than the crash speed it slides (the velocity loses its component into the ground); faster, it
// crashes where it hit.
StepOutcome collide(Aircraft& a, const GroundQuery& ground, const FlightParams& p) {
    const std::optional<GroundSample> g = ground ? ground(a.x, a.y) : std::nullopt;
    if (!g) {
        a.on_ground = false;
        return StepOutcome::Airborne;
    }
    const double floor = g->height_m + p.gear_height;
    if (a.z > floor) {
        if (a.z > floor + 0.5) a.on_ground = false;
        return a.on_ground ? StepOutcome::Sliding : StepOutcome::Airborne;
    }
    double v[3];
    a.velocity(&v[0], &v[1], &v[2]);
    const double into = -dot(v, g->normal);
    a.z = floor;
    if (into > p.crash_speed) return StepOutcome::Crashed;
    if (into > 0.0)
        for (int i = 0; i < 3; ++i) v[i] += into * g->normal[i];
    const double speed = std::sqrt(dot(v, v));
    a.speed = speed;
    if (speed > 0.01) {
        a.heading = std::atan2(v[0], v[1]);
        a.pitch = std::asin(std::clamp(v[2] / speed, -1.0, 1.0));
    }
    a.roll = 0.0;
    a.on_ground = true;
    return StepOutcome::Sliding;
}

}  // namespace

void Aircraft::velocity(double* vx, double* vy, double* vz) const {
    const double c = std::cos(pitch);
    *vx = speed * std::sin(heading) * c;
    *vy = speed * std::cos(heading) * c;
    *vz = speed * std::sin(pitch);
}

StepOutcome stepAircraft(Aircraft& a, const Controls& c, double dt, const GroundQuery& ground, const FlightParams& p) {
    const double drag = p.max_thrust / (p.top_speed * p.top_speed);
    StepOutcome outcome = a.on_ground ? StepOutcome::Sliding : StepOutcome::Airborne;
    forSubsteps(dt, p.substep, [&](double h) {
        // Attitude: rates from the stick; the wings level themselves when the stick is centred.
        a.roll += std::clamp(c.roll, -1.0, 1.0) * p.roll_rate * h;
        if (std::fabs(c.roll) < 0.05) a.roll -= std::copysign(std::min(std::fabs(a.roll), 0.4 * h), a.roll);
        a.roll = std::clamp(a.roll, -kMaxAttitude, kMaxAttitude);
        a.pitch = std::clamp(a.pitch + std::clamp(c.pitch, -1.0, 1.0) * p.pitch_rate * h, -kMaxAttitude, kMaxAttitude);
        // A banked aircraft turns (coordinated turn rate g tan(roll) / v), plus the rudder.
        const double turn = a.speed > 1.0 ? p.gravity * std::tan(a.roll) / a.speed : 0.0;
        a.heading = std::remainder(a.heading + (std::clamp(c.yaw, -1.0, 1.0) * p.yaw_rate + turn) * h, 2.0 * M_PI);
        a.throttle = std::clamp(a.throttle + 0.5 * std::clamp(c.throttle, -1.0, 1.0) * h, 0.0, 1.0);
        // Speed along the path: thrust, drag, gravity's share, friction while sliding.
        double accel = a.throttle * p.max_thrust - drag * a.speed * a.speed - p.gravity * std::sin(a.pitch);
        if (a.on_ground) accel -= p.ground_friction * p.gravity;
        a.speed = std::max(0.0, a.speed + accel * h);
        // Below the stall speed the nose drops.
        if (!a.on_ground && a.speed < p.stall_speed)
            a.pitch = std::max(-kMaxAttitude, a.pitch - (1.0 - a.speed / p.stall_speed) * 0.9 * h);
        double vx, vy, vz;
        a.velocity(&vx, &vy, &vz);
        a.x += vx * h;
        a.y += vy * h;
        a.z += vz * h;
        outcome = collide(a, ground, p);
        return outcome != StepOutcome::Crashed;
    });
    return outcome;
}

StepOutcome stepGuided(Aircraft& a, const Guidance& g, double dt, const GroundQuery& ground, const FlightParams& p) {
    StepOutcome outcome = StepOutcome::Airborne;
    a.on_ground = false;
    forSubsteps(dt, p.substep, [&](double h) {
        // Course changes at a standard rate (0.5 rad/s), banking into the turn.
        const double turn = std::clamp(std::remainder(g.heading - a.heading, 2.0 * M_PI), -0.5 * h, 0.5 * h);
        a.heading = std::remainder(a.heading + turn, 2.0 * M_PI);
        a.roll = std::atan(turn / h * g.horizontal_speed / p.gravity);
        const double vz_now = a.speed * std::sin(a.pitch);
        const double step = g.max_vertical_accel * h;
        const double vz = vz_now + std::clamp(g.vertical_speed - vz_now, -step, step);
        a.speed = std::hypot(g.horizontal_speed, vz);
        a.pitch = std::atan2(vz, g.horizontal_speed);
        a.x += g.horizontal_speed * std::sin(a.heading) * h;
        a.y += g.horizontal_speed * std::cos(a.heading) * h;
        a.z += vz * h;
        outcome = collide(a, ground, p);
        return outcome != StepOutcome::Crashed;
    });
    return outcome;
}

void stepBody(Body& b, double dt, const GroundQuery& ground, const BodyParams& p) {
    forSubsteps(dt, p.substep, [&](double h) {
        if (b.at_rest) return false;
        const double speed = std::sqrt(b.vx * b.vx + b.vy * b.vy + b.vz * b.vz);
        b.vx -= p.drag * speed * b.vx * h;
        b.vy -= p.drag * speed * b.vy * h;
        b.vz -= (p.gravity + p.drag * speed * b.vz) * h;
        b.x += b.vx * h;
        b.y += b.vy * h;
        b.z += b.vz * h;
        const std::optional<GroundSample> g = ground ? ground(b.x, b.y) : std::nullopt;
        if (!g || b.z > g->height_m) {
            b.in_contact = false;
            return true;
        }
        // Contact is inelastic: on the surface, moving along it.
        b.z = g->height_m;
        b.in_contact = true;
        double v[3] = {b.vx, b.vy, b.vz};
        const double vn = dot(v, g->normal);
        if (vn < 0.0)
            for (int i = 0; i < 3; ++i) v[i] -= vn * g->normal[i];
        // Coulomb friction against the normal force (gravity's share along the normal).
        const double nz = g->normal[2];
        const double friction = p.friction * p.gravity * nz * h;
        const double vt = std::sqrt(dot(v, v));
        const double slope_pull = p.gravity * std::sqrt(std::max(0.0, 1.0 - nz * nz));
        if (vt <= std::max(friction, p.rest_speed) && slope_pull <= p.friction * p.gravity * nz) {
            b.vx = b.vy = b.vz = 0.0;
            b.at_rest = true;
            return false;
        }
        const double scale = vt > friction ? (vt - friction) / vt : 0.0;
        b.vx = v[0] * scale;
        b.vy = v[1] * scale;
        b.vz = v[2] * scale;
        return true;
    });
}

}  // namespace terrasynth::game
