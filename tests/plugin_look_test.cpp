// The terrain's look (terrain_look.h) and home view, rendered by osgViewer under Xvfb (Mesa llvmpipe):
//  - a top view shows a spread of tints and shading (its luminance histogram is not one spike),
//    with vegetation low and snow high, where the old flat material under the headlight did not;
//  - the sun is fixed: turning the camera about the vertical does not change the light;
//  - the home view of a trackball manipulator (what stock osgviewer starts with) shows the whole
//    home extent obliquely from above, lit (not a black field).
// When DISPLAY is unset the test re-runs itself under xvfb-run; it skips only if xvfb-run is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <osg/DisplaySettings>
#include <osg/Material>
#include <osg/Program>
#include <osgDB/WriteFile>
#include <osgGA/TrackballManipulator>
#include <osgViewer/Viewer>

#include "render_support.h"
#include "terrasynth_plugin/terrain_node.h"
#include "test_support.h"
#include "wait_until.h"

namespace terrasynth::plugin {
namespace {

constexpr int kWidth = 480, kHeight = 270;
const osg::Vec4 kClear(1.0f, 0.0f, 1.0f, 1.0f);  // magenta: no terrain colour is ever this

bool isClear(const unsigned char* p) { return p[0] > 240 && p[1] < 15 && p[2] > 240; }
double luminance(const unsigned char* p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; }

struct Scene {
    Heightfield dem = test::loadExemplarField("orom_alaska");  // 280 to 6180 m: lowland to snow
    HeightSource source = mirroredExemplarSource(dem);
    osg::ref_ptr<TerrainNode> node;
    osgViewer::Viewer viewer;
    osg::ref_ptr<test::Capture> capture = new test::Capture(kWidth, kHeight);
    std::string window_error;

    explicit Scene(double fovy_deg) {
        TerrainNodeOptions o;
        o.tile_size = 64;
        o.max_level = 4;
        o.view_radius_m = 300000.0;  // the home view looks from 60 km beyond the extent's far side
        o.threads = 2;
        o.pixel_error = 3.0f;
        node = new TerrainNode(source, dem.meters_per_pixel_x, o);
        window_error = test::setUpWindowViewer(viewer, kWidth, kHeight, kClear, fovy_deg, capture.get());
        viewer.setSceneData(node.get());
    }
    // Frames until every wanted tile is drawn (however long that takes, within a deadline).
    void settle() {
        int frames = 0;
        EXPECT_TRUE(test::waitUntil([&] {
            viewer.frame();
            return ++frames > 4 && node->settled();
        })) << "the view never converged";
        viewer.frame();
    }
    void lookDownFrom(const osg::Vec3d& eye, const osg::Vec3d& up) {
        viewer.getCamera()->setViewMatrixAsLookAt(eye, eye - osg::Vec3d(0, 0, 1), up);
    }
    double meanLuminance() const {
        double sum = 0.0;
        int n = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const unsigned char* p = capture->image->data(x, y);
                if (isClear(p)) continue;
                sum += luminance(p);
                ++n;
            }
        return n ? sum / n : 0.0;
    }
};

struct Spread {
    double spike = 0.0;    // largest share of pixels within 16 adjacent luminance levels
    double p10_p90 = 0.0;  // luminance levels between the 10th and 90th percentiles
    double snow = 0.0, vegetation = 0.0, clear = 0.0;  // shares of pixels
};

Spread tintSpread(const osg::Image& image) {
    std::array<int, 256> histogram{};
    Spread s;
    int n = 0;
    for (int y = 0; y < image.t(); ++y)
        for (int x = 0; x < image.s(); ++x) {
            const unsigned char* p = image.data(x, y);
            if (isClear(p)) {
                s.clear += 1;
                continue;
            }
            ++histogram[static_cast<size_t>(std::lround(luminance(p)))];
            ++n;
            s.snow += p[0] > 200 && p[1] > 200 && p[2] > 200;
            s.vegetation += p[1] > p[0] + 4 && p[1] > p[2] + 8;
        }
    if (n == 0) return s;
    int window = 0;
    for (int v = 0; v < 256; ++v) {
        window += histogram[v] - (v >= 16 ? histogram[v - 16] : 0);
        s.spike = std::max(s.spike, double(window) / n);
    }
    int below = 0, p10 = -1, p90 = -1;
    for (int v = 0; v < 256; ++v) {
        below += histogram[v];
        if (p10 < 0 && below >= 0.1 * n) p10 = v;
        if (p90 < 0 && below >= 0.9 * n) p90 = v;
    }
    s.p10_p90 = p90 - p10;
    const double total = double(image.s()) * image.t();
    s.snow /= n;
    s.vegetation /= n;
    s.clear /= total;
    return s;
}

void topView() {
    Scene scene(40.0);
    ASSERT_EQ(scene.window_error, "");
    scene.node->setLook(lookForHeightRange(280.0f, 6180.0f));
    const double mpp = scene.dem.meters_per_pixel_x;
    const osg::Vec3d eye(324 * mpp, -324 * mpp, 45000.0);  // over the exemplar's middle
    scene.lookDownFrom(eye, osg::Vec3d(0, 1, 0));
    scene.settle();
    const std::string shots = test::scratchDir("plugin_look");
    osgDB::writeImageFile(*scene.capture->image, shots + "/top.png");
    const Spread look = tintSpread(*scene.capture->image);
    std::printf("top view: spike %.2f, p10-p90 %.0f levels, snow %.3f, vegetation %.3f\n", look.spike, look.p10_p90,
                look.snow, look.vegetation);
    EXPECT_LT(look.clear, 0.001) << "a top view is all terrain";
    EXPECT_LT(look.spike, 0.5) << "the luminance histogram is one spike";
    EXPECT_GT(look.p10_p90, 40.0);
    EXPECT_GT(look.snow, 0.005) << "no snow on the high ground";
    EXPECT_GT(look.vegetation, 0.02) << "no vegetation on the low ground";

    // The sun is fixed: the same ground seen with the camera turned half a turn is as bright.
    const double mean_north_up = scene.meanLuminance();
    scene.lookDownFrom(eye, osg::Vec3d(0, -1, 0));
    scene.settle();
    EXPECT_NEAR(scene.meanLuminance(), mean_north_up, 1.0) << "the light turned with the camera";

    // Control: the old look (one material colour under the viewer's headlight) reads as a plane.
    osg::ref_ptr<osg::StateSet> old_look = new osg::StateSet;
    old_look->setAttributeAndModes(new osg::Program, osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE);
    osg::ref_ptr<osg::Material> grey = new osg::Material;
    grey->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4(0.62f, 0.58f, 0.50f, 1.0f));
    grey->setAmbient(osg::Material::FRONT_AND_BACK, osg::Vec4(0.30f, 0.29f, 0.27f, 1.0f));
    old_look->setAttributeAndModes(grey.get(), osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE);
    scene.viewer.getCamera()->setStateSet(old_look.get());
    scene.settle();
    osgDB::writeImageFile(*scene.capture->image, shots + "/top_old_look.png");
    const Spread old_spread = tintSpread(*scene.capture->image);
    std::printf("old look: spike %.2f, p10-p90 %.0f levels\n", old_spread.spike, old_spread.p10_p90);
    EXPECT_GT(old_spread.spike, 0.5) << "the control should fail the criterion";
}

void homeView() {
    // Stock osgviewer's field of view (from the display settings' screen size and distance).
    const osg::DisplaySettings* ds = osg::DisplaySettings::instance().get();
    const double fovy = osg::RadiansToDegrees(2.0 * std::atan(0.5 * ds->getScreenHeight() / ds->getScreenDistance()));
    Scene scene(fovy);
    ASSERT_EQ(scene.window_error, "");
    const PixelWindow extent{0, 0, 648, 648};
    ASSERT_TRUE(scene.node->preload(extent, 4));
    ASSERT_TRUE(scene.node->preload(extent, 2));
    scene.node->setHomeExtent(extent);
    const auto range = scene.node->heightRange(extent);
    ASSERT_TRUE(range.has_value());
    scene.node->setLook(lookForHeightRange(range->first, range->second));
    scene.viewer.setCameraManipulator(new osgGA::TrackballManipulator);
    scene.viewer.home();
    scene.settle();
    osgDB::writeImageFile(*scene.capture->image, test::scratchDir("plugin_look_home") + "/home.png");

    const osg::Camera& cam = *scene.viewer.getCamera();
    const osg::Matrixd to_window = cam.getViewMatrix() * cam.getProjectionMatrix() * cam.getViewport()->computeWindowMatrix();
    const osg::Vec3d eye = osg::Vec3d() * cam.getInverseViewMatrix();
    const double mpp = scene.dem.meters_per_pixel_x, mid = 0.5 * (range->first + range->second);
    EXPECT_GT(eye.z(), range->second) << "the eye must be above every peak of the extent";
    // Every corner of the extent is on screen, in the lower half (seen from above).
    double far_edge_row = kHeight;
    for (int corner = 0; corner < 4; ++corner) {
        const osg::Vec3d world((corner % 2) * 648 * mpp, -(corner / 2) * 648 * mpp, mid);
        const osg::Vec3d w = world * to_window;
        EXPECT_GT(w.x(), 0.0) << "corner " << corner;
        EXPECT_LT(w.x(), kWidth) << "corner " << corner;
        EXPECT_GT(w.y(), 0.0) << "corner " << corner;
        EXPECT_LT(w.y(), 0.5 * kHeight) << "corner " << corner;
        if (corner < 2) far_edge_row = std::min(far_edge_row, w.y());
    }
    // Obliquely: the extent's middle is seen between 5 and 25 degrees below the horizontal.
    const osg::Vec3d centre(324 * mpp, -324 * mpp, mid), to_centre = centre - eye;
    const double depression = osg::RadiansToDegrees(std::atan2(-to_centre.z(), std::hypot(to_centre.x(), to_centre.y())));
    EXPECT_GT(depression, 5.0);
    EXPECT_LT(depression, 25.0);
    // Up to the extent's far edge the view is lit terrain, not a black field.
    int terrain = 0, rows = static_cast<int>(far_edge_row);
    double sum = 0.0;
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const unsigned char* p = scene.capture->image->data(x, y);
            if (isClear(p)) continue;
            ++terrain;
            sum += luminance(p);
        }
    EXPECT_GT(rows, kHeight / 8);
    EXPECT_GT(terrain, 0.99 * kWidth * rows);
    EXPECT_GT(sum / std::max(terrain, 1), 70.0) << "the home view is dark";
}

TEST(PluginLook, TopViewHasATintSpreadAndAFixedSun) {
    TERRASYNTH_NEED_DISPLAY("PluginLook.TopViewHasATintSpreadAndAFixedSun");
    topView();
}

TEST(PluginLook, HomeViewShowsTheExtentObliquelyFromAbove) {
    TERRASYNTH_NEED_DISPLAY("PluginLook.HomeViewShowsTheExtentObliquelyFromAbove");
    homeView();
}

}  // namespace
}  // namespace terrasynth::plugin
