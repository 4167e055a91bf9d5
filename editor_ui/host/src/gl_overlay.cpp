#include "gl_overlay.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include <osg/GLExtensions>
#include <osg/Image>
#include <osgDB/WriteFile>

#include <imgui.h>
#include <backends/imgui_impl_opengl2.h>

namespace terrasynth::host {

void drawImGuiOverOsg(osg::State& state) {
    // ImGui's OpenGL2 backend draws with the fixed-function pipeline from client-side arrays on
    // texture unit 0 and leaves every client array disabled. OSG 3.6 only re-enables an array it
    // believes disabled (State::dirtyAllVertexArrays is a no-op there), so disable them through OSG
    // first: afterwards its bookkeeping matches what ImGui leaves behind. Then leave OSG's program,
    // buffer objects and texture unit.
    state.disableAllVertexArrays();
    state.unbindVertexBufferObject();
    state.unbindElementBufferObject();
    state.setActiveTextureUnit(0);
    state.setClientActiveTextureUnit(0);
    if (const osg::GLExtensions* gl = state.get<osg::GLExtensions>(); gl && gl->isGlslSupported) gl->glUseProgram(0);

    ImGui::Render();
    ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());

    // The program was changed behind OSG's back: make it re-apply its program and, to be safe, every
    // attribute. Modes are left alone on purpose: the backend restores every enable it touches
    // (glPushAttrib(GL_ENABLE_BIT)), so OSG's record of them is still true, whereas
    // State::dirtyAllModes() *inverts* that record and OSG then skips the glEnable(GL_DEPTH_TEST)
    // the next frame needs (the terrain drew without depth testing).
    state.setLastAppliedProgramObject(nullptr);
    state.haveAppliedAttribute(osg::StateAttribute::PROGRAM);
    state.dirtyAllAttributes();
}

Status writeScreenshot(int width, int height, const std::string& path) {
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->readPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE);
    namespace fs = std::filesystem;
    const fs::path target(path);
    // osgDB picks the writer by extension, so the temporary name keeps ".png".
    const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".partial.png");
    if (!osgDB::writeImageFile(*image, temporary.string())) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        return Status::error(path + ": could not write the screenshot (is the folder writable?)");
    }
    std::error_code ec;
    fs::rename(temporary, target, ec);
    if (ec) {
        fs::remove(temporary, ec);
        return Status::error(path + ": could not move the screenshot into place: " + ec.message());
    }
    return Status::ok();
}

}  // namespace terrasynth::host
