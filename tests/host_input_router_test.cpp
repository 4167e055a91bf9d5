// Input routing between ImGui and the application (terrasynth_host/input_router.h), no window.
#include <gtest/gtest.h>

#include "terrasynth_host/input_router.h"

namespace terrasynth::host {
namespace {

constexpr int kKeyW = 87, kKeyA = 65;  // GLFW_KEY_W, GLFW_KEY_A

InputEvent mouse(InputEvent::Type type, int button = 0, double x = 10, double y = 10) {
    InputEvent e;
    e.type = type;
    e.button = button;
    e.x = x;
    e.y = y;
    return e;
}
InputEvent key(InputEvent::Type type, int k) {
    InputEvent e;
    e.type = type;
    e.key = k;
    return e;
}
using T = InputEvent::Type;

TEST(InputRouter, HoverAndWheelGoWhereImGuiDoesNotWantTheMouse) {
    InputRouter r;
    EXPECT_TRUE(r.route(mouse(T::MouseMove), false, false));
    EXPECT_FALSE(r.route(mouse(T::MouseMove), true, false));
    EXPECT_TRUE(r.route(mouse(T::Scroll), false, false));
    EXPECT_FALSE(r.route(mouse(T::Scroll), true, false));
}

TEST(InputRouter, TheFirstPressOwnsTheDragUntilEveryButtonIsUp) {
    InputRouter r;
    // Pressed over the 3D view: the drag stays with the application across a panel.
    EXPECT_TRUE(r.route(mouse(T::MouseDown, 0), false, false));
    EXPECT_TRUE(r.mouseDown(0));
    EXPECT_TRUE(r.route(mouse(T::MouseMove), true, false));
    EXPECT_TRUE(r.route(mouse(T::MouseDown, 1), true, false));  // a second button joins the drag
    EXPECT_TRUE(r.route(mouse(T::MouseUp, 0), true, false));
    EXPECT_TRUE(r.route(mouse(T::MouseMove), true, true));
    EXPECT_TRUE(r.route(mouse(T::MouseUp, 1), true, false));
    EXPECT_FALSE(r.mouseDown(0));
    // Pressed over a panel: nothing of the drag reaches the application, not even over the view.
    EXPECT_FALSE(r.route(mouse(T::MouseDown, 0), true, false));
    EXPECT_FALSE(r.mouseDown(0));
    EXPECT_FALSE(r.route(mouse(T::MouseMove), false, false));
    EXPECT_FALSE(r.route(mouse(T::MouseUp, 0), false, false));
    // Afterwards hover is routed by ImGui's wish again.
    EXPECT_TRUE(r.route(mouse(T::MouseMove), false, false));
}

TEST(InputRouter, AReleaseWithoutAPressIsNotRouted) {
    InputRouter r;
    EXPECT_FALSE(r.route(mouse(T::MouseUp, 0), false, false));
    EXPECT_FALSE(r.route(key(T::KeyUp, kKeyW), false, false));
    EXPECT_FALSE(r.route(mouse(T::MouseDown, 99), false, false));  // unknown button
}

TEST(InputRouter, AKeyReleaseFollowsItsPress) {
    InputRouter r;
    EXPECT_TRUE(r.route(key(T::KeyDown, kKeyW), false, false));
    EXPECT_TRUE(r.keyDown(kKeyW));
    // A text field takes the keyboard: W's repeats and release still reach the application, which
    // holds it; a new key goes to ImGui only.
    EXPECT_TRUE(r.route(key(T::KeyRepeat, kKeyW), false, true));
    EXPECT_FALSE(r.route(key(T::KeyDown, kKeyA), false, true));
    EXPECT_FALSE(r.keyDown(kKeyA));
    EXPECT_FALSE(r.route(key(T::KeyRepeat, kKeyA), false, true));
    EXPECT_TRUE(r.route(key(T::KeyUp, kKeyW), false, true));
    EXPECT_FALSE(r.keyDown(kKeyW));
    EXPECT_FALSE(r.route(key(T::KeyUp, kKeyA), false, true));
    InputEvent c;
    c.type = T::Char;
    c.codepoint = 'x';
    EXPECT_FALSE(r.route(c, false, true));
    EXPECT_TRUE(r.route(c, false, false));
}

TEST(InputRouter, ReleaseAllGivesBackWhatTheApplicationHeld) {
    InputRouter r;
    r.route(key(T::KeyDown, kKeyW), false, false);
    r.route(mouse(T::MouseDown, 2, 5, 6), false, false);
    const std::vector<InputEvent> released = r.releaseAll();
    ASSERT_EQ(released.size(), 2u);
    EXPECT_EQ(released[0].type, T::KeyUp);
    EXPECT_EQ(released[0].key, kKeyW);
    EXPECT_EQ(released[1].type, T::MouseUp);
    EXPECT_EQ(released[1].button, 2);
    EXPECT_EQ(released[1].x, 5);
    EXPECT_FALSE(r.keyDown(kKeyW));
    EXPECT_FALSE(r.mouseDown(2));
    EXPECT_TRUE(r.releaseAll().empty());
}

}  // namespace
}  // namespace terrasynth::host
