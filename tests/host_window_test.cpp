// The window/GL host (terrasynth_host/host_window.h) in a real window under Xvfb (Mesa llvmpipe):
// ImGui draws over OSG, geometry added after ImGui drew still draws (OpenSceneGraph issue 924),
// injected input reaches ImGui or OSG as the routing says, screenshots and frame timing.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <osg/Geometry>
#include <osg/Group>
#include <osgDB/ReadFile>
#include <osgGA/GUIEventHandler>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "terrasynth_host/host_window.h"
#include "test_support.h"

namespace terrasynth::host {
namespace {

constexpr int kW = 320, kH = 240;

// An unlit, single-colour rectangle in the unit square at height z (nearer the camera when larger), drawn from VBOs like the terrain tiles.
osg::ref_ptr<osg::Geometry> rectangle(float x0, float x1, float z, const osg::Vec4& colour) {
    osg::ref_ptr<osg::Geometry> g = osg::createTexturedQuadGeometry(osg::Vec3(x0, 0, z), osg::Vec3(x1 - x0, 0, 0),
                                                                    osg::Vec3(0, 1, 0));
    osg::ref_ptr<osg::Vec4Array> colours = new osg::Vec4Array;
    colours->push_back(colour);
    g->setColorArray(colours.get(), osg::Array::BIND_OVERALL);
    g->setUseDisplayList(false);
    g->setUseVertexBufferObjects(true);
    return g;
}

struct EventRecorder : osgGA::GUIEventHandler {
    std::vector<osgGA::GUIEventAdapter::EventType> types;
    std::vector<int> keys;
    bool handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter&) override {
        const auto t = ea.getEventType();
        if (t == osgGA::GUIEventAdapter::PUSH || t == osgGA::GUIEventAdapter::RELEASE ||
            t == osgGA::GUIEventAdapter::DRAG || t == osgGA::GUIEventAdapter::KEYDOWN ||
            t == osgGA::GUIEventAdapter::KEYUP)
            types.push_back(t);
        if (t == osgGA::GUIEventAdapter::KEYDOWN) keys.push_back(ea.getKey());
        return false;
    }
    int count(osgGA::GUIEventAdapter::EventType t) const {
        int n = 0;
        for (auto x : types) n += x == t;
        return n;
    }
};

// RGB of window pixel (x, y), y from the top, in a screenshot read back from disk.
osg::Vec3i pixel(const osg::Image& image, int x, int y) {
    const unsigned char* p = image.data(x, image.t() - 1 - y);
    return {p[0], p[1], p[2]};
}
bool isRed(const osg::Vec3i& p) { return p.x() > 200 && p.y() < 40 && p.z() < 40; }
bool isGreen(const osg::Vec3i& p) { return p.x() < 40 && p.y() > 200 && p.z() < 40; }
bool isClear(const osg::Vec3i& p) { return p.x() < 40 && p.y() < 40 && p.z() > 200; }

void runChecks() {
    HostOptions options;
    options.width = kW;
    options.height = kH;
    options.title = "host_window_test";
    options.clear_color = {0.0f, 0.0f, 1.0f, 1.0f};
    auto created = HostWindow::create(options);
    ASSERT_TRUE(created) << created.message();
    HostWindow& host = **created;
    EXPECT_EQ(host.width(), kW);
    EXPECT_EQ(host.height(), kH);

    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    root->addChild(rectangle(0.0f, 1.0f, 0.0f, {1, 0, 0, 1}));
    osg::Camera* camera = host.viewer().getCamera();
    camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    camera->setProjectionMatrixAsOrtho(0, 1, 0, 1, -1, 1);
    camera->setViewMatrix(osg::Matrix::identity());
    osg::ref_ptr<EventRecorder> recorder = new EventRecorder;
    host.viewer().addEventHandler(recorder.get());
    host.viewer().setSceneData(root.get());

    bool button_pressed = false;
    auto frame = [&] {
        host.beginFrame();
        ImGui::SetNextWindowPos(ImVec2(10, 10));
        ImGui::SetNextWindowSize(ImVec2(140, 90));
        ImGui::Begin("Panel", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
        if (ImGui::Button("Press", ImVec2(100, 30))) button_pressed = true;
        ImGui::End();
        return host.endFrame();
    };
    const std::string dir = test::scratchDir("host_window");
    auto shot = [&](const std::string& name, bool overlay) -> osg::ref_ptr<osg::Image> {
        host.requestScreenshot(dir + "/" + name, overlay);
        frame();
        EXPECT_TRUE(host.lastScreenshotStatus()) << host.lastScreenshotStatus().message();
        EXPECT_FALSE(std::filesystem::exists(dir + "/." + name + ".partial.png"));
        osg::ref_ptr<osg::Image> image = osgDB::readImageFile(dir + "/" + name);
        EXPECT_TRUE(image.valid()) << name;
        return image;
    };

    for (int i = 0; i < 3; ++i) frame();
    // The overlay is drawn over the 3D view; the 3D view alone has no panel.
    osg::ref_ptr<osg::Image> with = shot("with_overlay.png", true);
    ASSERT_TRUE(with.valid());
    EXPECT_EQ(with->s(), kW);
    EXPECT_TRUE(isRed(pixel(*with, 250, 200)));
    EXPECT_FALSE(isRed(pixel(*with, 70, 80)));
    EXPECT_FALSE(isClear(pixel(*with, 70, 80)));
    osg::ref_ptr<osg::Image> without = shot("without_overlay.png", false);
    ASSERT_TRUE(without.valid());
    EXPECT_TRUE(isRed(pixel(*without, 70, 80)));

    // Geometry attached after ImGui has drawn still draws (OSG's cached state was marked dirty).
    root->addChild(rectangle(0.5f, 1.0f, 0.5f, {0, 1, 0, 1}));
    frame();
    osg::ref_ptr<osg::Image> added = shot("added_after_overlay.png", true);
    ASSERT_TRUE(added.valid());
    EXPECT_TRUE(isGreen(pixel(*added, 280, 200))) << "geometry added after the overlay drew is missing";
    EXPECT_TRUE(isRed(pixel(*added, 100, 200)));
    // Depth testing still works after the overlay: a farther rectangle drawn after the green one
    // stays hidden behind it.
    root->addChild(rectangle(0.5f, 1.0f, -0.5f, {1, 1, 0, 1}));
    frame();
    osg::ref_ptr<osg::Image> depth = shot("depth_after_overlay.png", true);
    ASSERT_TRUE(depth.valid());
    EXPECT_TRUE(isGreen(pixel(*depth, 280, 200))) << "the overlay broke depth testing";

    // Depth testing still works after ImGui drew: a nearer rectangle drawn first hides a farther one
    // drawn after it (the host must not leave OSG believing a mode is enabled when it is not).
    osg::ref_ptr<osg::Group> layered = new osg::Group;
    layered->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    layered->addChild(rectangle(0.0f, 1.0f, 0.5f, {0, 1, 0, 1}));
    layered->addChild(rectangle(0.0f, 1.0f, -0.5f, {1, 0, 0, 1}));
    host.viewer().setSceneData(layered.get());
    for (int i = 0; i < 3; ++i) frame();
    osg::ref_ptr<osg::Image> layered_shot = shot("depth.png", true);
    ASSERT_TRUE(layered_shot.valid());
    EXPECT_TRUE(isGreen(pixel(*layered_shot, 250, 200))) << "the farther rectangle drawn last covered the nearer one";
    host.viewer().setSceneData(root.get());
    frame();

    // Images for ImGui: a solid-colour texture drawn with ImGui::Image shows its colour.
    std::vector<uint8_t> blue_pixels(16 * 16 * 4, 255);
    for (size_t i = 0; i < blue_pixels.size(); i += 4) blue_pixels[i] = blue_pixels[i + 1] = 0;
    const ImTextureID blue = host.uploadImage(blue_pixels, 16, 16);
    auto image_frame = [&] {
        host.beginFrame();
        ImGui::SetNextWindowPos(ImVec2(170, 10));
        ImGui::SetNextWindowSize(ImVec2(120, 100));
        ImGui::Begin("Image", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
        ImGui::Image(blue, ImVec2(64, 48));
        ImGui::End();
        return host.endFrame();
    };
    image_frame();
    host.requestScreenshot(dir + "/image.png", true);
    image_frame();
    osg::ref_ptr<osg::Image> with_image = osgDB::readImageFile(dir + "/image.png");
    ASSERT_TRUE(with_image.valid());
    const osg::Vec3i texel = pixel(*with_image, 170 + 8 + 32, 10 + 30 + 20);
    EXPECT_TRUE(texel.x() < 40 && texel.y() < 40 && texel.z() > 200) << texel.x() << "," << texel.y() << "," << texel.z();
    host.releaseImage(blue);
    frame();

    // A click on the panel's button reaches ImGui only.
    recorder->types.clear();
    host.injectMouseMove(60, 50);
    host.injectMouseButton(0, true);
    frame();
    EXPECT_TRUE(host.routedEvents().empty());
    host.injectMouseButton(0, false);
    frame();
    frame();
    EXPECT_TRUE(button_pressed) << "the injected click did not press the ImGui button";
    EXPECT_EQ(recorder->count(osgGA::GUIEventAdapter::PUSH), 0);
    EXPECT_EQ(recorder->count(osgGA::GUIEventAdapter::RELEASE), 0);

    // A drag started on the 3D view stays with OSG over the panel, release included.
    button_pressed = false;
    host.injectMouseMove(250, 200);
    frame();
    host.injectMouseButton(0, true);
    frame();
    ASSERT_FALSE(host.routedEvents().empty());
    EXPECT_EQ(host.routedEvents().back().type, InputEvent::Type::MouseDown);
    EXPECT_TRUE(host.mouseDown(0));
    host.injectMouseMove(60, 50);
    frame();
    host.injectMouseButton(0, false);
    frame();
    EXPECT_FALSE(host.mouseDown(0));
    EXPECT_EQ(recorder->count(osgGA::GUIEventAdapter::PUSH), 1);
    EXPECT_GE(recorder->count(osgGA::GUIEventAdapter::DRAG), 1);
    EXPECT_EQ(recorder->count(osgGA::GUIEventAdapter::RELEASE), 1);
    EXPECT_FALSE(button_pressed);

    // Keys: held on the application side, given to osgGA as its symbols.
    host.injectKey(GLFW_KEY_W, true);
    frame();
    EXPECT_TRUE(host.keyDown(GLFW_KEY_W));
    ASSERT_FALSE(recorder->keys.empty());
    EXPECT_EQ(recorder->keys.back(), 'w');
    host.injectKey(GLFW_KEY_W, false);
    frame();
    EXPECT_FALSE(host.keyDown(GLFW_KEY_W));

    // Timing: every part measured, the parts fit in the frame.
    const FrameTiming t = frame();
    EXPECT_GT(t.frame_ms, 0.0);
    EXPECT_GT(t.draw_ms, 0.0);
    for (double part : {t.events_ms, t.app_ms, t.update_ms, t.cull_ms, t.overlay_ms, t.swap_ms}) EXPECT_GE(part, 0.0);
    EXPECT_LE(t.events_ms + t.app_ms + t.update_ms + t.cull_ms + t.draw_ms + t.overlay_ms + t.swap_ms,
              t.frame_ms + 1e-6);
    EXPECT_NEAR(t.mainThreadMs() + t.glMs(), t.frame_ms, 1e-9);

    // Screenshots into a folder that does not exist fail with the path in the message.
    host.requestScreenshot(dir + "/missing/shot.png", true);
    frame();
    EXPECT_FALSE(host.lastScreenshotStatus());
    EXPECT_NE(host.lastScreenshotStatus().message().find("missing/shot.png"), std::string::npos);

    EXPECT_FALSE(host.closeRequested());
    host.requestClose();
    EXPECT_FALSE(host.beginFrame());
    host.endFrame();
}

TEST(HostWindow, OverlayRoutingScreenshotsAndTiming) {
    TERRASYNTH_NEED_DISPLAY("HostWindow.*");
    runChecks();
}

}  // namespace
}  // namespace terrasynth::host
