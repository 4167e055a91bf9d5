#include "terrasynth_game/chase_camera.h"

#include <algorithm>
#include <cmath>

namespace terrasynth::game {

CameraPose chaseCamera(const Aircraft& a, const std::function<std::optional<double>(double, double)>& ground,
                       const ChaseSettings& s) {
    // Follow the heading and half the pitch: steep climbs stay in view without the horizon tilting.
    const double pitch = 0.5 * a.pitch;
    const osg::Vec3d forward(std::sin(a.heading) * std::cos(pitch), std::cos(a.heading) * std::cos(pitch), std::sin(pitch));
    const osg::Vec3d position(a.x, a.y, a.z);
    CameraPose pose;
    pose.eye = position - forward * s.behind_m + osg::Vec3d(0.0, 0.0, s.above_m);
    pose.center = position + forward * s.look_ahead_m;
    if (ground) {
        if (const std::optional<double> g = ground(pose.eye.x(), pose.eye.y()))
            pose.eye.z() = std::max(pose.eye.z(), *g + s.min_clearance_m);
    }
    return pose;
}

}  // namespace terrasynth::game
