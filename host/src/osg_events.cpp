#include "osg_events.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <osgGA/GUIEventAdapter>

namespace terrasynth::host {
namespace {
using Key = osgGA::GUIEventAdapter::KeySymbol;

struct KeyPair {
    int glfw;
    int osg;
};
constexpr KeyPair kNamedKeys[] = {
    {GLFW_KEY_ESCAPE, Key::KEY_Escape},       {GLFW_KEY_ENTER, Key::KEY_Return},
    {GLFW_KEY_TAB, Key::KEY_Tab},             {GLFW_KEY_BACKSPACE, Key::KEY_BackSpace},
    {GLFW_KEY_INSERT, Key::KEY_Insert},       {GLFW_KEY_DELETE, Key::KEY_Delete},
    {GLFW_KEY_RIGHT, Key::KEY_Right},         {GLFW_KEY_LEFT, Key::KEY_Left},
    {GLFW_KEY_DOWN, Key::KEY_Down},           {GLFW_KEY_UP, Key::KEY_Up},
    {GLFW_KEY_PAGE_UP, Key::KEY_Page_Up},     {GLFW_KEY_PAGE_DOWN, Key::KEY_Page_Down},
    {GLFW_KEY_HOME, Key::KEY_Home},           {GLFW_KEY_END, Key::KEY_End},
    {GLFW_KEY_LEFT_SHIFT, Key::KEY_Shift_L},  {GLFW_KEY_RIGHT_SHIFT, Key::KEY_Shift_R},
    {GLFW_KEY_LEFT_CONTROL, Key::KEY_Control_L}, {GLFW_KEY_RIGHT_CONTROL, Key::KEY_Control_R},
    {GLFW_KEY_LEFT_ALT, Key::KEY_Alt_L},      {GLFW_KEY_RIGHT_ALT, Key::KEY_Alt_R},
    {GLFW_KEY_LEFT_SUPER, Key::KEY_Super_L},  {GLFW_KEY_RIGHT_SUPER, Key::KEY_Super_R},
    {GLFW_KEY_KP_ENTER, Key::KEY_KP_Enter},
};

}  // namespace

int osgKeySymbol(int key, int mods) {
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z)
        return (mods & GLFW_MOD_SHIFT) ? key : key - GLFW_KEY_A + 'a';
    // GLFW's printable keys other than letters are their US-layout ASCII codes.
    if (key == GLFW_KEY_SPACE || (key >= GLFW_KEY_APOSTROPHE && key <= GLFW_KEY_GRAVE_ACCENT)) return key;
    if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F12) return Key::KEY_F1 + (key - GLFW_KEY_F1);
    if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) return Key::KEY_KP_0 + (key - GLFW_KEY_KP_0);
    for (const KeyPair& p : kNamedKeys)
        if (p.glfw == key) return p.osg;
    return 0;
}

void forwardToOsg(const InputEvent& e, osgGA::EventQueue& q) {
    using T = InputEvent::Type;
    const auto x = static_cast<float>(e.x), y = static_cast<float>(e.y);
    // osgGA numbers buttons 1 left, 2 middle, 3 right; GLFW 0 left, 1 right, 2 middle.
    auto osgButton = [](int b) { return b == 0 ? 1u : b == 1 ? 3u : b == 2 ? 2u : static_cast<unsigned>(b + 1); };
    switch (e.type) {
        case T::MouseMove:
            q.mouseMotion(x, y);
            break;
        case T::MouseDown:
            q.mouseButtonPress(x, y, osgButton(e.button));
            break;
        case T::MouseUp:
            q.mouseButtonRelease(x, y, osgButton(e.button));
            break;
        case T::Scroll:
            if (e.scroll_y != 0.0)
                q.mouseScroll(e.scroll_y > 0 ? osgGA::GUIEventAdapter::SCROLL_UP : osgGA::GUIEventAdapter::SCROLL_DOWN);
            break;
        case T::KeyDown:
        case T::KeyRepeat:
            if (int k = osgKeySymbol(e.key, e.mods)) q.keyPress(k);
            break;
        case T::KeyUp:
            if (int k = osgKeySymbol(e.key, e.mods)) q.keyRelease(k);
            break;
        case T::Char:
            break;  // osgGA has no text input; key presses carry the symbols
    }
}

}  // namespace terrasynth::host
