// terrasynth_host/input_router.h: who gets an input event, ImGui or the application (and OSG).
//
// ImGui sees every event first (its backend gets them all); the router decides which ones also go
// to the application side (the viewer's event queue and HostWindow::routedEvents):
//  - a mouse press goes to the application when ImGui does not want the mouse, and then the whole
//    drag (moves, other buttons, the releases) stays with whoever got that first press until every
//    button is up, even if the pointer crosses a panel;
//  - hover moves and wheel steps go to the application when ImGui does not want the mouse;
//  - a key press goes to the application when ImGui does not want the keyboard, and so do its
//    repeats and its release (no key gets stuck down on either side); characters likewise.
// Plain logic, no GL or ImGui calls (the caller passes ImGui's WantCapture* flags), so it is unit
// tested on its own. Not thread-safe.
#pragma once

#include <bitset>
#include <vector>

#include "terrasynth_host/input_event.h"

namespace terrasynth::host {

class InputRouter {
public:
    // True if `e` goes to the application. Updates drag and key ownership and the held state.
    bool route(const InputEvent& e, bool imgui_wants_mouse, bool imgui_wants_keyboard);
    // Keys / buttons the application currently holds (pressed on its side, not yet released).
    bool keyDown(int glfw_key) const;
    bool mouseDown(int button) const;
    // Releases everything the application holds (e.g. when the window loses focus) and returns the
    // KeyUp / MouseUp events it would have received.
    std::vector<InputEvent> releaseAll();

private:
    enum class Owner { None, ImGui, App };
    static constexpr int kKeys = 512;  // GLFW_KEY_LAST is 348
    static constexpr int kButtons = 8;

    Owner drag_owner_ = Owner::None;
    std::bitset<kButtons> buttons_down_;   // every button held, whoever owns the drag
    std::bitset<kKeys> app_keys_;          // keys whose press went to the application
    double last_x_ = 0.0, last_y_ = 0.0;
};

}  // namespace terrasynth::host
