// The game's ImGui panels: the flight HUD, the loading screen, an error screen. ImGui calls only
// (the host draws them); all numbers come in through plain structs.
#pragma once

#include <cstdint>
#include <string>

namespace terrasynth::game {

struct HudData {
    double speed_ms = 0.0;
    double altitude_m = 0.0;       // above sea level
    double above_ground_m = 0.0;   // above the ground under the aircraft
    bool ground_exact = false;     // the ground height is exact (else from the drawn tiles)
    bool ground_known = false;
    double x_km = 0.0, y_km = 0.0;
    uint32_t seed = 0;
    size_t resident_tiles = 0, pending_tiles = 0, drawn_triangles = 0;
    double frame_ms = 0.0;         // smoothed
    double throttle = 0.0;
    bool autopilot = false;
    int rings_collected = 0;
    bool ring_ahead = false;
    double ring_distance_m = 0.0, ring_bearing_deg = 0.0;  // to the nearest open ring, bearing relative to the nose
    std::string message;           // e.g. "crashed: respawned at the last safe point"
};

void drawHud(const HudData& d);
void drawLoading(const std::string& stage, double progress, double elapsed_s);
void drawFatal(const std::string& message);

}  // namespace terrasynth::game
