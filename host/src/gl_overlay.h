// The host's only GL calls: ImGui drawn over OSG's frame, and screenshots. Private to the host.
#pragma once

#include <string>
#include <vector>

#include <osg/State>

#include "terrasynth/status.h"

namespace terrasynth::host {

// Renders ImGui's current frame (ImGui::Render must not have been called yet) over the viewport,
// entering from OSG's GL state and leaving OSG's state tracker true to what GL then is, so the
// next OSG draw re-applies what it needs (geometry merged after an overlay drew would otherwise
// stop drawing, because OSG believes client arrays are still enabled).
void drawImGuiOverOsg(osg::State& state);

// Texture uploads for ImGui images, done while the overlay owns the GL state (unit 0 active).
struct ImageUpload {
    unsigned texture = 0;  // GL name from newImageTexture()
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};
unsigned newImageTexture();
// Uploads (then clears) `uploads` and deletes `doomed` (then clears), then renders ImGui as
// drawImGuiOverOsg does.
void drawImGuiOverOsg(osg::State& state, std::vector<ImageUpload>& uploads, std::vector<unsigned>& doomed);

// Reads the current draw buffer (width x height, RGB) and writes it as a PNG at `path`, atomically
// (a temporary file beside it, then rename). Errors name the file.
Status writeScreenshot(int width, int height, const std::string& path);

}  // namespace terrasynth::host
