// Perspective canvas (Bradbury et al. 2014 s4.1): ground-plane homography from the horizon and the
// grid lines, silhouette strokes to ridges. Ground truth comes from a pinhole camera whose image the
// "artist" traces.
#include <gtest/gtest.h>

#include <cmath>

#include "terrasynth/layers.h"

namespace terrasynth {
namespace {

// Level camera (no pitch, no roll) looking north from terrain pixel (128, 400), 200 m up; 10 m per
// terrain pixel; focal 800 px; 800x600 image with the principal point at its centre.
struct Camera {
    double mpp = 10.0, x0 = 128, y0 = 400, height_m = 200, f = 800, cu = 400, cv = 300;
    Point2 project(double x_px, double y_px, double z_m) const {
        const double depth_m = (y0 - y_px) * mpp;
        return {cu + f * (x_px - x0) * mpp / depth_m, cv + f * (height_m - z_m) / depth_m};
    }
};

PerspectiveCanvas canvasFor(const Camera& cam) {
    PerspectiveCanvas c;
    c.image_width = 800, c.image_height = 600;
    c.horizon = {{0, cam.cv}, {800, cam.cv}};
    // The artist drags the outer grid lines onto the ground square x 64..192, y 100..300.
    c.grid_left = {cam.project(64, 300, 0), cam.project(64, 100, 0)};
    c.grid_right = {cam.project(192, 300, 0), cam.project(192, 100, 0)};
    c.grid_near = {cam.project(64, 300, 0), cam.project(192, 300, 0)};
    c.grid_far = {cam.project(64, 100, 0), cam.project(192, 100, 0)};
    c.ground = {Point2{64, 300}, Point2{192, 300}, Point2{192, 100}, Point2{64, 100}};
    c.camera_height_m = cam.height_m;
    return c;
}

double ridgeHeight(double x) { return 150.0 + 100.0 * std::sin((x - 80.0) / 100.0 * M_PI); }

TEST(LayersPerspective, HomographyMapsTheGridAndPredictsTheHorizon) {
    const Camera cam;
    auto m = solvePerspective(canvasFor(cam));
    ASSERT_TRUE(m) << m.message();
    // Any ground point lands where the camera sees it, and back.
    for (auto [x, y] : {std::pair{100.0, 150.0}, std::pair{70.0, 280.0}, std::pair{180.0, 110.0}, std::pair{128.0, 50.0}}) {
        const Point2 img = m->ground_to_image.apply({x, y});
        const Point2 truth = cam.project(x, y, 0);
        EXPECT_NEAR(img.x, truth.x, 1e-6);
        EXPECT_NEAR(img.y, truth.y, 1e-6);
        const Point2 back = m->image_to_ground.apply(truth);
        EXPECT_NEAR(back.x, x, 1e-6);
        EXPECT_NEAR(back.y, y, 1e-6);
    }
    // The grid's vanishing line is the true horizon.
    const Line2 v = vanishingLine(m->ground_to_image);
    EXPECT_NEAR(v.a.y, cam.cv, 1e-6);
    EXPECT_NEAR(v.b.y, cam.cv, 1e-6);
}

TEST(LayersPerspective, SilhouetteStrokeBecomesTheRidgeTheCameraSaw) {
    const Camera cam;
    SilhouetteStroke stroke;
    for (double x = 80; x <= 180; x += 5) stroke.points.push_back(cam.project(x, 200, ridgeHeight(x)));
    stroke.base_v = cam.project(128, 200, 0).y;  // the ridge stands on the ground line y = 200
    stroke.width_px = 6;
    auto ridges = strokesToRidges(canvasFor(cam), {stroke});
    ASSERT_TRUE(ridges) << ridges.message();
    ASSERT_EQ(ridges->size(), 1u);
    const RidgeParams& r = (*ridges)[0];
    // Positions: along terrain row 200, from x 80 to 180.
    ASSERT_EQ(r.points.size(), stroke.points.size());
    for (size_t i = 0; i < r.points.size(); ++i) {
        EXPECT_NEAR(r.points[i][0], 80 + 5.0 * i, 1e-6);
        EXPECT_NEAR(r.points[i][1], 200, 1e-6);
    }
    // Heights: single-view metrology recovers the true elevations.
    for (size_t k = 0; k < r.profile_m.size(); ++k) {
        const double x = 80 + 100.0 * k / (r.profile_m.size() - 1);
        EXPECT_NEAR(r.profile_m[k], ridgeHeight(x), 1e-6 * 250);
    }
    // The same drawn height means more metres farther away (s4.1: elevation from depth).
    SilhouetteStroke near_stroke = stroke, far_stroke = stroke;
    near_stroke.points = {{300, 380}, {500, 380}};
    near_stroke.base_v = 420;
    far_stroke.points = {{300, 330}, {500, 330}};
    far_stroke.base_v = 370;
    auto both = strokesToRidges(canvasFor(cam), {near_stroke, far_stroke});
    ASSERT_TRUE(both);
    EXPECT_NEAR((*both)[0].profile_m[0], 200.0 * 40 / 120, 1e-9);  // H (vb - vt) / (vb - vh)
    EXPECT_NEAR((*both)[1].profile_m[0], 200.0 * 40 / 70, 1e-9);
    EXPECT_LT((*both)[1].points[0][1], (*both)[0].points[0][1]);  // farther = more north
}

TEST(LayersPerspective, PerspectiveLayerRaisesTheRidgeOnTheHeightfield) {
    const Camera cam;
    PerspectiveParams p;
    p.canvas = canvasFor(cam);
    SilhouetteStroke stroke;
    for (double x = 80; x <= 180; x += 5) stroke.points.push_back(cam.project(x, 200, ridgeHeight(x)));
    stroke.base_v = cam.project(128, 200, 0).y;
    stroke.width_px = 10;
    p.strokes = {stroke};
    LayerStack stack;
    stack.base.source = BaseSource::Blank;
    EditLayer layer;
    layer.tool = p;
    layer.weights = BandWeights{};  // all bands, so the crest is exact
    stack.layers.push_back(layer);
    auto out = applyLayerStack(stack, Heightfield(256, 256, cam.mpp));
    ASSERT_TRUE(out) << out.message();
    EXPECT_NEAR(out->at(130, 200), ridgeHeight(130), 0.5);
    EXPECT_NEAR(out->at(130, 150), 0.0, 0.5);
    EXPECT_NEAR(out->at(130, 210), ridgeHeight(130) * std::exp(-0.5), 1.0);
    // By default (low band only) the sketch sets the large-scale shape.
    EXPECT_EQ(defaultWeights(layer.tool), (BandWeights{1, 0, 0}));
}

TEST(LayersPerspective, BadCanvasesAreNamedErrors) {
    const Camera cam;
    PerspectiveCanvas c = canvasFor(cam);
    c.grid_far = {{0, 250}, {800, 250}};  // above the horizon
    auto m = solvePerspective(c);
    ASSERT_FALSE(m);
    EXPECT_NE(m.message().find("grid_far"), std::string::npos) << m.message();
    c = canvasFor(cam);
    c.grid_right = c.grid_left;
    EXPECT_FALSE(solvePerspective(c));
    SilhouetteStroke above;
    above.points = {{100, 200}, {200, 210}};
    above.base_v = 250;  // foot above the horizon
    auto r = strokesToRidges(canvasFor(cam), {above});
    ASSERT_FALSE(r);
    EXPECT_NE(r.message().find("strokes[0].base_v"), std::string::npos) << r.message();
    EXPECT_FALSE(homographyFromPoints({Point2{0, 0}, Point2{1, 1}, Point2{2, 2}, Point2{0, 1}},
                                      {Point2{0, 0}, Point2{1, 0}, Point2{1, 1}, Point2{0, 1}}));
}

}  // namespace
}  // namespace terrasynth
