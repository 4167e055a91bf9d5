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

#include <osg/Camera>
#include <osg/GraphicsContext>
#include <osg/Image>
#include <osgDB/WriteFile>
#include <osgViewer/Viewer>

#include "terrasynth_plugin/terrain_node.h"
#include "test_support.h"

namespace terrasynth::plugin {
namespace {

constexpr int kWidth = 480, kHeight = 270;
constexpr double kPitchDeg = 12.0;  // below the horizon: the sky (clear colour) stays in view
const osg::Vec4 kClear(1.0f, 0.0f, 1.0f, 1.0f);  // magenta: no terrain colour is ever this

struct Capture : osg::Camera::DrawCallback {
    osg::ref_ptr<osg::Image> image = new osg::Image;
    void operator()(osg::RenderInfo&) const override {
        image->readPixels(0, 0, kWidth, kHeight, GL_RGB, GL_UNSIGNED_BYTE);
    }
};

// Pixels that must show terrain: their ray descends and reaches `ground_z` (at or below every drawn
// sample, so the terrain is hit first) within `radius` metres horizontally of the eye.
int countHoles(const osg::Image& img, const osg::Camera& cam, double ground_z, double radius, int* required,
               int* sky) {
    const osg::Matrixd vpw = cam.getViewMatrix() * cam.getProjectionMatrix() *
                             cam.getViewport()->computeWindowMatrix();
    const osg::Matrixd inv = osg::Matrixd::inverse(vpw);
    osg::Vec3d eye, center, up;
    cam.getViewMatrixAsLookAt(eye, center, up);
    int holes = 0;
    *required = 0;
    *sky = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const osg::Vec3d a = osg::Vec3d(x + 0.5, y + 0.5, 0.0) * inv, b = osg::Vec3d(x + 0.5, y + 0.5, 1.0) * inv;
            const osg::Vec3d dir = b - a;
            const unsigned char* p = img.data(x, y);
            const bool clear = p[0] > 240 && p[1] < 15 && p[2] > 240;
            if (dir.z() >= -1e-9) {
                *sky += clear;
                continue;
            }
            const double t = (ground_z - eye.z()) / dir.z();
            const osg::Vec3d hit = eye + dir * t;
            if (std::hypot(hit.x() - eye.x(), hit.y() - eye.y()) > radius) continue;
            ++*required;
            holes += clear;
        }
    }
    return holes;
}

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

    osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
    traits->readDISPLAY();
    traits->setUndefinedScreenDetailsToDefaultScreen();
    traits->width = kWidth;
    traits->height = kHeight;
    traits->windowDecoration = false;
    traits->doubleBuffer = true;
    osg::ref_ptr<osg::GraphicsContext> gc = osg::GraphicsContext::createGraphicsContext(traits.get());
    ASSERT_TRUE(gc.valid()) << "no graphics context (DISPLAY=" << (std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "")
                            << ")";
    osgViewer::Viewer viewer;
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    osg::Camera* cam = viewer.getCamera();
    cam->setGraphicsContext(gc.get());
    cam->setViewport(0, 0, kWidth, kHeight);
    cam->setProjectionMatrixAsPerspective(40.0, double(kWidth) / kHeight, 1.0, 1e6);
    cam->setClearColor(kClear);
    osg::ref_ptr<Capture> capture = new Capture;
    cam->setFinalDrawCallback(capture.get());
    viewer.setSceneData(terrain.get());
    viewer.realize();
    ASSERT_TRUE(viewer.isRealized());

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
        // few settled pauses so that fully refined views are checked too.
        const bool pause = s == 0 || s % 10 == 0;
        for (int f = 0; f < (pause ? 400 : 2); ++f) {
            viewer.frame();
            ++frames;
            if (pause && f > 3 && terrain->settled()) break;
            if (pause) std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        const TerrainStats st = terrain->stats();
        ASSERT_GT(st.drawn_tiles, 0u);
        int required = 0, sky = 0;
        const int holes = countHoles(*capture->image, *cam, st.drawn_min_height - 1.0,
                                     0.9 * terrain->options().view_radius_m, &required, &sky);
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
    const int rc = test::rerunUnderXvfbUnlessDisplay("PluginRender.FlightShowsNoHolesOrCracks");
    if (rc == test::kNoXvfb) GTEST_SKIP() << "no DISPLAY and no xvfb-run";
    if (rc != test::kHaveDisplay) {
        ASSERT_EQ(rc, 0) << "the flight under xvfb-run failed (its output is above)";
        return;
    }
    runFlight();
}

}  // namespace
}  // namespace terrasynth::plugin
