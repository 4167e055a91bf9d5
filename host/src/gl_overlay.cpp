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

unsigned newImageTexture() {
    GLuint name = 0;
    glGenTextures(1, &name);
    return name;
}

void drawImGuiOverOsg(osg::State& state, std::vector<ImageUpload>& uploads, std::vector<unsigned>& doomed) {
    if (!uploads.empty() || !doomed.empty()) {
        // Unit 0 is OSG's to track: bind through GL, then put back what OSG believes is bound.
        state.setActiveTextureUnit(0);
        GLint bound = 0;
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (const ImageUpload& u : uploads) {
            glBindTexture(GL_TEXTURE_2D, u.texture);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, u.width, u.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, u.rgba.data());
        }
        for (unsigned name : doomed) {
            const GLuint n = name;
            glDeleteTextures(1, &n);
        }
        glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound));
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        uploads.clear();
        doomed.clear();
    }
    drawImGuiOverOsg(state);
}

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
