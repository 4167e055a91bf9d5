// Routed input events into osgGA's event queue (manipulators and event handlers), private to the host.
#pragma once

#include <osgGA/EventQueue>

#include "terrasynth_host/input_event.h"

namespace terrasynth::host {

// osgGA key symbol of a GLFW key ('a'..'z' lower case unless Shift is held, KEY_* for the rest),
// or 0 when osgGA has no symbol for it.
int osgKeySymbol(int glfw_key, int glfw_mods);

void forwardToOsg(const InputEvent& e, osgGA::EventQueue& queue);

}  // namespace terrasynth::host
