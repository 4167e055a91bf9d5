// terrasynth_game/chase_camera.h: where the camera is, following the aircraft.
//
// Behind the aircraft along its heading and above it, looking a little past it; the eye never goes
// below min_clearance_m above the ground under it (when the ground there is known). A pure function
// of the aircraft's state, so a replayed flight sees the same frames.
#pragma once

#include <functional>
#include <optional>

#include <osg/Vec3d>

#include "terrasynth_game/flight_model.h"

namespace terrasynth::game {

struct CameraPose {
    osg::Vec3d eye, center, up{0.0, 0.0, 1.0};
};

struct ChaseSettings {
    double behind_m = 55.0;
    double above_m = 14.0;
    double look_ahead_m = 60.0;
    double min_clearance_m = 2.0;
};

// `ground`: height under a world point, nullopt when unknown.
CameraPose chaseCamera(const Aircraft& a, const std::function<std::optional<double>(double, double)>& ground,
                       const ChaseSettings& s = {});

}  // namespace terrasynth::game
