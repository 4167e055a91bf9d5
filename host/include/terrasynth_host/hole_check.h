// terrasynth_host/hole_check.h: the "no holes" criterion of a rendered terrain frame.
//
// A pixel must show terrain when its view ray descends and meets the plane z = ground_z (at or below
// every drawn sample, so the terrain is hit first) within radius_m metres horizontally of the eye.
// Such a pixel showing the clear colour is a hole (a missing tile, a crack between LODs). Pixels
// whose ray rises are sky; counting the clear colour there proves the check can see it.
// Used by plugin_render_test and by the demo game's test mode. Plain CPU work, no GL.
#pragma once

#include <osg/Camera>
#include <osg/Image>
#include <osg/Vec4>

namespace terrasynth::host {

struct HoleCount {
    int holes = 0;      // pixels that must show terrain but show the clear colour
    int required = 0;   // pixels that must show terrain
    int sky_clear = 0;  // pixels above the horizon showing the clear colour
};

// `image`: GL_RGB, 8 bits per channel, as read back from the camera's viewport (row 0 at the
// bottom). A pixel is the clear colour when every channel is within `tolerance` of it (0..255).
HoleCount countHoles(const osg::Image& image, const osg::Camera& camera, double ground_z, double radius_m,
                     const osg::Vec4& clear_colour, int tolerance = 15);

}  // namespace terrasynth::host
