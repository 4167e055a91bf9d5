// terrasynth_host/input_event.h: one input event as the host routes it (plain data).
//
// Events come from the window system (GLFW callbacks) or are injected by a script
// (HostWindow::inject*). Keys are GLFW key codes (GLFW_KEY_*), buttons GLFW mouse buttons
// (0 left, 1 right, 2 middle), positions window pixels with the origin at the top-left corner.
#pragma once

#include <cstdint>

namespace terrasynth::host {

struct InputEvent {
    enum class Type { KeyDown, KeyRepeat, KeyUp, Char, MouseMove, MouseDown, MouseUp, Scroll };
    Type type = Type::MouseMove;
    int key = 0;             // KeyDown/KeyRepeat/KeyUp: GLFW_KEY_*
    int mods = 0;            // GLFW_MOD_* bits
    uint32_t codepoint = 0;  // Char: Unicode code point
    int button = 0;          // MouseDown/MouseUp: 0 left, 1 right, 2 middle
    double x = 0.0, y = 0.0; // mouse events: window pixels, origin top-left
    double scroll_x = 0.0, scroll_y = 0.0;  // Scroll: wheel steps
    bool injected = false;   // came from inject*() rather than the window system

    bool isKey() const { return type == Type::KeyDown || type == Type::KeyRepeat || type == Type::KeyUp; }
    bool isMouse() const {
        return type == Type::MouseMove || type == Type::MouseDown || type == Type::MouseUp || type == Type::Scroll;
    }
};

}  // namespace terrasynth::host
