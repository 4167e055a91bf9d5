// Headless render of a camera flight over the terrain (osgViewer in a window under Xvfb, Mesa
// llvmpipe). Every captured frame is checked pixel by pixel: a pixel whose view ray descends and
// meets the lowest drawn ground well inside the drawn radius must show terrain, never the clear
// colour, whatever LODs are mixed on screen (a hole or a crack between LODs would show it).
// When DISPLAY is unset the test re-runs itself under xvfb-run; it skips only if xvfb-run is missing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include <osgDB/WriteFile>
#include <osgViewer/Viewer>

#include "render_support.h"
#include "terrasynth_host/hole_check.h"
#include "terrasynth_plugin/terrain_node.h"
#include "test_support.h"
#include "wait_until.h"

namespace terrasynth::plugin {
namespace {

constexpr int kWidth = 480, kHeight = 270;
constexpr double kPitchDeg = 12.0;  // below the horizon: the sky (clear colour) stays in view
const osg::Vec4 kClear(1.0f, 0.0f, 1.0f, 1.0f);  // magenta: no terrain colour is ever this

void runFlight() {
    const Heightfield dem = test::loadExemplarField("orom_alaska");
    HeightSource source = mirroredExemplarSource(dem);
    TerrainNodeOptions o;
    o.tile_size = 64;
    o.max_level = 4;
    o.threads = 2;
    o.pixel_error = 3.0f;
    o.merge_budget_ms = 4.0;
    osg::ref_ptr<TerrainNode> terrain = new TerrainNode(source, dem.meters_per_pixel_x, o);

    osgViewer::Viewer viewer;
    osg::ref_ptr<test::Capture> capture = new test::Capture(kWidth, kHeight);
    const std::string no_window = test::setUpWindowViewer(viewer, kWidth, kHeight, kClear, 40.0, capture.get());
    ASSERT_EQ(no_window, "");
    osg::Camera* cam = viewer.getCamera();
    viewer.setSceneData(terrain.get());

    const std::string shots = test::scratchDir("plugin_render");
    // Terrain-following flight, 10 km east-south-east at 700 m above the ground below, looking
    // 12 degrees down (sky in the top rows): near tiles at level 0, distant ones coarse, LOD boundaries everywhere.
    auto groundAt = [&](double wx, double wy) {
        auto h = source({static_cast<int64_t>(wx / dem.meters_per_pixel_x),
                         static_cast<int64_t>(-wy / dem.meters_per_pixel_x), 1, 1}, 0);
        return h ? double(h->at(0, 0)) : 0.0;
    };
    const osg::Vec3d start(21000, -17000, 0), heading = osg::Vec3d(0.93, -0.37, 0.0) / 1.0;
    const double flight_m = 10000.0;
    const int steps = 30;
    int frames = 0, checked = 0, required_total = 0, sky_total = 0;
    for (int s = 0; s <= steps; ++s) {
        osg::Vec3d eye = start + heading * (flight_m * s / steps);
        eye.z() = groundAt(eye.x(), eye.y()) + 700.0;
        const osg::Vec3d look = heading * std::cos(osg::DegreesToRadians(kPitchDeg)) +
                                osg::Vec3d(0, 0, -std::sin(osg::DegreesToRadians(kPitchDeg)));
        cam->setViewMatrixAsLookAt(eye, eye + look, osg::Vec3d(0, 0, 1));
        // At the start wait for the roots; afterwards keep flying whatever is still loading, with a
        // few settled pauses (as long as the workers take) so that fully refined views are checked too.
        if (s == 0 || s % 10 == 0) {
            int paused = 0;
            EXPECT_TRUE(test::waitUntil([&] {
                viewer.frame();
                ++frames;
                return ++paused > 4 && terrain->settled();
            }, std::chrono::minutes(10), std::chrono::milliseconds(5))) << "step " << s << ": the view never converged";
        } else {
            for (int f = 0; f < 2; ++f, ++frames) viewer.frame();
        }
        const TerrainStats st = terrain->stats();
        ASSERT_GT(st.drawn_tiles, 0u);
        const host::HoleCount count = host::countHoles(*capture->image, *cam, st.drawn_min_height - 1.0,
                                                       0.9 * terrain->options().view_radius_m, kClear);
        const int holes = count.holes, required = count.required, sky = count.sky_clear;
        sky_total += sky;
        required_total += required;
        ++checked;
        if (s % 5 == 0 || holes)
            osgDB::writeImageFile(*capture->image, shots + "/flight_" + std::to_string(s) + ".png");
        EXPECT_EQ(holes, 0) << "step " << s << ": " << holes << " background pixels below the horizon ("
                            << required << " checked, " << st.drawn_tiles << " tiles drawn)";
    }
    EXPECT_GT(required_total, checked * kWidth * kHeight / 4) << "the flight must look at the ground";
    // The check can fail: the clear colour is really on screen where there is no terrain (sky).
    EXPECT_GT(sky_total, checked * kWidth) << "the sky should be visible above the horizon";
    const TerrainStats st = terrain->stats();
    EXPECT_EQ(st.build_failures, 0u);
    std::printf("flight: %d frames, %d checked, %llu tiles built, max merge %.3f ms, resident %zu tiles\n", frames,
                checked, static_cast<unsigned long long>(st.tiles_built), st.max_merge_ms, st.resident_tiles);
}

TEST(PluginRender, FlightShowsNoHolesOrCracks) {
    TERRASYNTH_NEED_DISPLAY("PluginRender.FlightShowsNoHolesOrCracks");
    runFlight();
}

}  // namespace
}  // namespace terrasynth::plugin
