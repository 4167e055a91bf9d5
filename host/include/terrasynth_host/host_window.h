// terrasynth_host/host_window.h: one window that hosts an OSG view with a Dear ImGui overlay.
//
// The window/GL glue shared by the editor (editor_ui/) and the demo game (demo_game/):
//  - a GLFW 3.3 window with a compatibility-profile GL context (Debian's OSG 3.6.5 is a GL2 build);
//  - an osgViewer::Viewer embedded in it (setUpViewerAsEmbeddedInWindow), single-threaded, so OSG
//    draws into the context GLFW made current and the host swaps;
//  - Dear ImGui (Debian libimgui-dev 1.86: GLFW + OpenGL2 backends, pre-1.87 input API) drawn last,
//    over the 3D view. ImGui changes GL state behind OSG's back (client arrays, program, buffers),
//    so after it draws the host tells OSG's state tracker that everything it cached is unknown
//    (otherwise OSG believes client arrays are still enabled and geometry merged later stops drawing);
//  - input routed to ImGui first and to OSG (the viewer's event queue: manipulators, handlers) and
//    the application only when ImGui does not want it. Whoever gets a mouse press owns the drag until
//    the last button is released; whoever gets a key press gets its release;
//  - event injection for scripted runs: injected events take the same route as real ones, applied
//    after the ImGui backend polled the window (the 1.86 GLFW backend reads the mouse by polling);
//  - per-frame timing (frame_stats.h) and screenshots read back from the frame being drawn;
//  - images (RGBA pixels) as textures for ImGui::Image, uploaded while the overlay draws.
//
// A frame is beginFrame() -> the application's work (read routedEvents(), move the camera, build
// ImGui windows) -> endFrame(). Panels and game code only talk to ImGui and OSG; GL calls stay here.
//
// Threading: everything on the thread that created the window (GLFW and the GL context require it).
// One HostWindow per process (GLFW and ImGui keep global state).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <osg/Image>
#include <imgui.h>
#include <osg/Vec4>
#include <osg/ref_ptr>
#include <osgViewer/Viewer>

#include "terrasynth/status.h"
#include "terrasynth_host/frame_stats.h"
#include "terrasynth_host/input_event.h"

namespace terrasynth::host {

struct HostOptions {
    int width = 1280, height = 720;  // window (and framebuffer) size in pixels, >= 16
    std::string title = "terrasynth";
    bool vsync = false;              // swap interval 1; off for benchmarks
    bool resizable = true;
    double fovy_deg = 40.0;          // vertical field of view of the viewer's camera
    osg::Vec4 clear_color{0.62f, 0.72f, 0.85f, 1.0f};
    // glFinish after the OSG draw so FrameTiming::draw_ms holds the rasterizer's work rather than
    // showing up in the next frame's swap. Costs a pipeline drain on a real GPU; fine for a host
    // whose frame loop is the only GL client.
    bool finish_gl_for_timing = true;
    float ui_scale = 1.0f;           // ImGui font and style scale
};

class HostWindow {
public:
    // Opens the window and GL context, embeds a single-threaded viewer and initialises ImGui.
    // Errors (no display, no GL context, GLFW init failure) carry GLFW's own description.
    static Result<std::unique_ptr<HostWindow>> create(const HostOptions& options);
    ~HostWindow();
    HostWindow(const HostWindow&) = delete;
    HostWindow& operator=(const HostWindow&) = delete;

    // The embedded viewer: set its scene data, camera manipulator and event handlers. Do not call
    // its frame() or run(): beginFrame/endFrame drive it.
    osgViewer::Viewer& viewer() { return *viewer_; }

    // Starts a frame: polls the window system, starts the ImGui frame (ImGui calls are allowed until
    // endFrame), applies injected events and routes this frame's events. Returns false when the
    // window was asked to close (close button or requestClose()); the frame has still begun.
    bool beginFrame();
    // Events of this frame that ImGui did not take, in order (what the application acts on; they
    // were also given to the viewer's event queue).
    const std::vector<InputEvent>& routedEvents() const { return routed_; }
    // Keys and buttons currently held by the application's side of the routing (not by ImGui).
    bool keyDown(int glfw_key) const;
    bool mouseDown(int button) const;
    // Runs the viewer (event, update, cull, draw traversals) at `simulation_time_s` (< 0: wall
    // clock), draws ImGui over it, takes a requested screenshot, swaps. Returns the frame's timing.
    FrameTiming endFrame(double simulation_time_s = -1.0);

    // Asks beginFrame to report a close (like the window's close button). The environment variable
    // OSG_RUN_FRAME_COUNT=N, which osgViewer's run() obeys (osgviewer quits after N frames), does the
    // same here after N endFrame calls, so the editor and the game can be run for a few frames as
    // printed (the README commands' test, tests/readme_commands_test.py); unset, 0 or not a number: no limit.
    void requestClose();
    bool closeRequested() const;

    // Reads the next endFrame's image back to a PNG (atomically: temporary file, then rename).
    // with_overlay: after ImGui drew (what the user sees); otherwise the 3D view alone.
    void requestScreenshot(const std::string& png_path, bool with_overlay);
    // Result of the last screenshot taken: ok, or why it could not be written.
    const Status& lastScreenshotStatus() const { return screenshot_status_; }
    // Reads the next endFrame's image (GL_RGB, row 0 at the bottom) into `image` instead of a file,
    // for checks on what was drawn. The caller keeps `image` alive until that endFrame returns.
    void requestCapture(osg::Image* image, bool with_overlay);

    // Images for ImGui::Image (thumbnails, previews): `rgba` is width x height RGBA8, row 0 at the top.
    // Returns the texture id to draw (usable in this frame already: the pixels are uploaded when
    // the overlay draws); passing a previous id of the same size replaces its pixels. Textures live
    // until releaseImage or the window closes.
    ImTextureID uploadImage(const std::vector<uint8_t>& rgba, int width, int height, ImTextureID previous = nullptr);
    void releaseImage(ImTextureID image);

    // Scripted input, applied at the next beginFrame in the order given, routed like real input.
    void injectKey(int glfw_key, bool pressed, int mods = 0);
    void injectChar(uint32_t codepoint);
    void injectMouseMove(double x, double y);
    void injectMouseButton(int button, bool pressed, int mods = 0);
    void injectScroll(double dx, double dy);

    // The GL implementation frames are drawn with (GL_RENDERER), e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    const std::string& glRenderer() const { return gl_renderer_; }
    int width() const { return width_; }
    int height() const { return height_; }
    const HostOptions& options() const { return options_; }

    struct Impl;  // GLFW/ImGui/GL side (host_window.cpp); public only for the C callbacks there

private:
    explicit HostWindow(const HostOptions& options);

    HostOptions options_;
    int width_ = 0, height_ = 0;
    osg::ref_ptr<osgViewer::Viewer> viewer_;
    std::unique_ptr<Impl> impl_;
    std::vector<InputEvent> routed_;
    std::string gl_renderer_;
    Status screenshot_status_ = Status::ok();
};

}  // namespace terrasynth::host
