#include "terrasynth_host/input_router.h"

namespace terrasynth::host {

bool InputRouter::route(const InputEvent& e, bool imgui_wants_mouse, bool imgui_wants_keyboard) {
    using T = InputEvent::Type;
    const bool valid_button = e.button >= 0 && e.button < kButtons;
    const bool valid_key = e.key >= 0 && e.key < kKeys;
    if (e.isMouse()) {
        last_x_ = e.x;
        last_y_ = e.y;
    }
    switch (e.type) {
        case T::MouseDown: {
            if (!valid_button) return false;
            if (buttons_down_.none()) drag_owner_ = imgui_wants_mouse ? Owner::ImGui : Owner::App;
            buttons_down_.set(static_cast<size_t>(e.button));
            return drag_owner_ == Owner::App;
        }
        case T::MouseUp: {
            if (!valid_button || !buttons_down_.test(static_cast<size_t>(e.button))) return false;
            const bool to_app = drag_owner_ == Owner::App;
            buttons_down_.reset(static_cast<size_t>(e.button));
            if (buttons_down_.none()) drag_owner_ = Owner::None;
            return to_app;
        }
        case T::MouseMove:
        case T::Scroll:
            if (drag_owner_ != Owner::None) return drag_owner_ == Owner::App;
            return !imgui_wants_mouse;
        case T::KeyDown:
            if (!valid_key) return false;
            if (imgui_wants_keyboard) return false;
            app_keys_.set(static_cast<size_t>(e.key));
            return true;
        case T::KeyRepeat:
            return valid_key && app_keys_.test(static_cast<size_t>(e.key));
        case T::KeyUp: {
            if (!valid_key || !app_keys_.test(static_cast<size_t>(e.key))) return false;
            app_keys_.reset(static_cast<size_t>(e.key));
            return true;
        }
        case T::Char:
            return !imgui_wants_keyboard;
    }
    return false;
}

bool InputRouter::keyDown(int key) const {
    return key >= 0 && key < kKeys && app_keys_.test(static_cast<size_t>(key));
}

bool InputRouter::mouseDown(int button) const {
    return drag_owner_ == Owner::App && button >= 0 && button < kButtons &&
           buttons_down_.test(static_cast<size_t>(button));
}

std::vector<InputEvent> InputRouter::releaseAll() {
    std::vector<InputEvent> out;
    for (int k = 0; k < kKeys; ++k) {
        if (!app_keys_.test(static_cast<size_t>(k))) continue;
        InputEvent e;
        e.type = InputEvent::Type::KeyUp;
        e.key = k;
        out.push_back(e);
    }
    if (drag_owner_ == Owner::App) {
        for (int b = 0; b < kButtons; ++b) {
            if (!buttons_down_.test(static_cast<size_t>(b))) continue;
            InputEvent e;
            e.type = InputEvent::Type::MouseUp;
            e.button = b;
            e.x = last_x_;
            e.y = last_y_;
            out.push_back(e);
        }
    }
    app_keys_.reset();
    buttons_down_.reset();
    drag_owner_ = Owner::None;
    return out;
}

}  // namespace terrasynth::host
