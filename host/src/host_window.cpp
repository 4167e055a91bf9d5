// HostWindow: the GLFW window, the embedded single-threaded viewer, ImGui, input routing, timing.
#include "terrasynth_host/host_window.h"

#include <time.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <atomic>
#include <chrono>
#include <cstdlib>

#include <osg/GL>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl2.h>

#include "gl_overlay.h"
#include "osg_events.h"
#include "terrasynth_host/input_router.h"

namespace terrasynth::host {
namespace {

using Clock = std::chrono::steady_clock;
double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

double cpuMs(clockid_t clock) {
    timespec t{};
    clock_gettime(clock, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}
double threadCpuMs() { return cpuMs(CLOCK_THREAD_CPUTIME_ID); }
double processCpuMs() { return cpuMs(CLOCK_PROCESS_CPUTIME_ID); }

std::string g_glfw_error;  // GLFW reports errors through a C callback
void onGlfwError(int code, const char* description) {
    g_glfw_error = std::string(description ? description : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}
std::atomic<bool> g_window_alive{false};

// Marks the end of the cull (the draw starts) and drains the GL pipeline at the end of the draw.
struct DrawStartMarker : osg::Camera::DrawCallback {
    Clock::time_point* at;
    double* cpu;
    DrawStartMarker(Clock::time_point* t, double* c) : at(t), cpu(c) {}
    void operator()(osg::RenderInfo&) const override {
        *at = Clock::now();
        *cpu = processCpuMs();
    }
};
struct FinishDraw : osg::Camera::DrawCallback {
    void operator()(osg::RenderInfo&) const override { glFinish(); }
};

}  // namespace

struct HostWindow::Impl {
    GLFWwindow* window = nullptr;
    bool imgui_glfw = false, imgui_gl = false;
    osg::ref_ptr<osgViewer::GraphicsWindowEmbedded> embedded;
    InputRouter router;
    std::vector<InputEvent> pending;   // from the window system since the last beginFrame
    std::vector<InputEvent> injected;  // from inject*() since the last beginFrame
    bool mouse_injected = false;       // once a script moves the mouse, it owns ImGui's mouse state
    double mouse_x = 0.0, mouse_y = 0.0;
    std::array<bool, 5> mouse_held{}, mouse_pressed{};
    bool close_requested = false;
    long frames_left = 0;  // OSG_RUN_FRAME_COUNT's frames still to end; 0: no limit
    bool first_frame = true;
    Clock::time_point frame_start, app_start, draw_start;
    double frame_start_cpu = 0.0, draw_start_cpu = 0.0;
    double events_ms = 0.0;
    std::string screenshot_path;
    bool screenshot_with_overlay = false;
    osg::ref_ptr<osg::Image> capture;
    bool capture_with_overlay = false;
    std::vector<ImageUpload> uploads;  // image pixels waiting for the overlay step
    std::vector<unsigned> doomed;      // image textures to delete there
    std::vector<unsigned> images;      // live image textures

    static Impl& of(GLFWwindow* w) { return *static_cast<Impl*>(glfwGetWindowUserPointer(w)); }
    void push(InputEvent e) { pending.push_back(e); }
    void applyInjectedToImGui();
};

// --- window-system callbacks: ImGui first (its backend), then queued for routing ---------------

namespace {

void onKey(GLFWwindow* w, int key, int scancode, int action, int mods) {
    ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
    if (key == GLFW_KEY_UNKNOWN) return;
    InputEvent e;
    e.type = action == GLFW_PRESS ? InputEvent::Type::KeyDown
             : action == GLFW_REPEAT ? InputEvent::Type::KeyRepeat : InputEvent::Type::KeyUp;
    e.key = key;
    e.mods = mods;
    HostWindow::Impl::of(w).push(e);
}

void onChar(GLFWwindow* w, unsigned int codepoint) {
    ImGui_ImplGlfw_CharCallback(w, codepoint);
    InputEvent e;
    e.type = InputEvent::Type::Char;
    e.codepoint = codepoint;
    HostWindow::Impl::of(w).push(e);
}

void onMouseButton(GLFWwindow* w, int button, int action, int mods) {
    ImGui_ImplGlfw_MouseButtonCallback(w, button, action, mods);
    InputEvent e;
    e.type = action == GLFW_PRESS ? InputEvent::Type::MouseDown : InputEvent::Type::MouseUp;
    e.button = button;
    e.mods = mods;
    glfwGetCursorPos(w, &e.x, &e.y);
    HostWindow::Impl::of(w).push(e);
}

void onCursorPos(GLFWwindow* w, double x, double y) {
    // ImGui's 1.86 backend polls the cursor itself; only the routing needs the moves.
    InputEvent e;
    e.type = InputEvent::Type::MouseMove;
    e.x = x;
    e.y = y;
    HostWindow::Impl::of(w).push(e);
}

void onScroll(GLFWwindow* w, double dx, double dy) {
    ImGui_ImplGlfw_ScrollCallback(w, dx, dy);
    InputEvent e;
    e.type = InputEvent::Type::Scroll;
    e.scroll_x = dx;
    e.scroll_y = dy;
    glfwGetCursorPos(w, &e.x, &e.y);
    HostWindow::Impl::of(w).push(e);
}

void onFocus(GLFWwindow* w, int focused) {
    ImGui_ImplGlfw_WindowFocusCallback(w, focused);
    // Keys released while another window had the focus never reach us: release them now.
    if (!focused) {
        HostWindow::Impl& impl = HostWindow::Impl::of(w);
        for (InputEvent& e : impl.router.releaseAll()) impl.push(e);
    }
}

void onCursorEnter(GLFWwindow* w, int entered) { ImGui_ImplGlfw_CursorEnterCallback(w, entered); }

}  // namespace

void HostWindow::Impl::applyInjectedToImGui() {
    ImGuiIO& io = ImGui::GetIO();
    mouse_pressed.fill(false);
    for (const InputEvent& e : injected) {
        using T = InputEvent::Type;
        switch (e.type) {
            case T::KeyDown:
            case T::KeyRepeat:
            case T::KeyUp:
                ImGui_ImplGlfw_KeyCallback(window, e.key, 0,
                                           e.type == T::KeyDown ? GLFW_PRESS
                                           : e.type == T::KeyRepeat ? GLFW_REPEAT : GLFW_RELEASE,
                                           e.mods);
                break;
            case T::Char:
                io.AddInputCharacter(e.codepoint);
                break;
            case T::MouseMove:
            case T::MouseDown:
            case T::MouseUp:
                mouse_injected = true;
                mouse_x = e.x;
                mouse_y = e.y;
                if (e.button >= 0 && e.button < static_cast<int>(mouse_held.size())) {
                    if (e.type == T::MouseDown) mouse_held[e.button] = mouse_pressed[e.button] = true;
                    if (e.type == T::MouseUp) mouse_held[e.button] = false;
                }
                break;
            case T::Scroll:
                io.MouseWheel += static_cast<float>(e.scroll_y);
                io.MouseWheelH += static_cast<float>(e.scroll_x);
                break;
        }
    }
    if (!mouse_injected) return;
    // After the backend polled the (real) cursor: the script's mouse replaces it. A press and its
    // release in the same frame still count as held for this frame, as the backend does.
    io.MousePos = ImVec2(static_cast<float>(mouse_x), static_cast<float>(mouse_y));
    for (size_t b = 0; b < mouse_held.size(); ++b) io.MouseDown[b] = mouse_held[b] || mouse_pressed[b];
}

// --- HostWindow ------------------------------------------------------------------------------

HostWindow::HostWindow(const HostOptions& options) : options_(options), impl_(std::make_unique<Impl>()) {}

Result<std::unique_ptr<HostWindow>> HostWindow::create(const HostOptions& o) {
    TERRASYNTH_REQUIRE(o.width >= 16 && o.height >= 16, "window size must be at least 16x16");
    TERRASYNTH_REQUIRE(!g_window_alive.load(), "one HostWindow per process");
    glfwSetErrorCallback(onGlfwError);
    g_glfw_error.clear();
    if (!glfwInit()) return Status::error("cannot open a window: " + g_glfw_error);
    glfwDefaultWindowHints();
    // A legacy (compatibility) context: Debian's OSG is a GL2 build using the fixed-function state.
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
    glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_RESIZABLE, o.resizable ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(o.width, o.height, o.title.c_str(), nullptr, nullptr);
    if (!window) {
        const std::string why = g_glfw_error;
        glfwTerminate();
        return Status::error("cannot create a " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                             " OpenGL window: " + why);
    }
    g_window_alive = true;
    std::unique_ptr<HostWindow> host(new HostWindow(o));
    Impl& impl = *host->impl_;
    impl.window = window;
    // As osgViewer's run() reads it (a count of frames, then done).
    if (const char* count = std::getenv("OSG_RUN_FRAME_COUNT")) impl.frames_left = std::max(0L, std::strtol(count, nullptr, 10));
    glfwMakeContextCurrent(window);
    glfwSwapInterval(o.vsync ? 1 : 0);
    if (const GLubyte* renderer = glGetString(GL_RENDERER)) host->gl_renderer_ = reinterpret_cast<const char*>(renderer);
    glfwSetWindowUserPointer(window, &impl);
    glfwGetFramebufferSize(window, &host->width_, &host->height_);

    // The viewer draws into the context GLFW made current; the host polls and swaps.
    host->viewer_ = new osgViewer::Viewer;
    osgViewer::Viewer& viewer = *host->viewer_;
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    viewer.setKeyEventSetsDone(0);  // the application decides what quits
    viewer.setQuitEventSetsDone(false);
    impl.embedded = viewer.setUpViewerAsEmbeddedInWindow(0, 0, host->width_, host->height_);
    osg::Camera* camera = viewer.getCamera();
    camera->setClearColor(o.clear_color);
    camera->setProjectionMatrixAsPerspective(o.fovy_deg, double(host->width_) / host->height_, 1.0, 1e5);
    camera->setInitialDrawCallback(new DrawStartMarker(&impl.draw_start, &impl.draw_start_cpu));
    if (o.finish_gl_for_timing) camera->setFinalDrawCallback(new FinishDraw);
    viewer.realize();

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini left in the working folder
    ImGui::StyleColorsDark();
    if (o.ui_scale != 1.0f) {
        ImGui::GetStyle().ScaleAllSizes(o.ui_scale);
        io.FontGlobalScale = o.ui_scale;
    }
    impl.imgui_glfw = ImGui_ImplGlfw_InitForOpenGL(window, /*install_callbacks=*/false);
    impl.imgui_gl = ImGui_ImplOpenGL2_Init();
    if (!impl.imgui_glfw || !impl.imgui_gl) return Status::error("cannot initialise Dear ImGui's GLFW/OpenGL2 backends");

    glfwSetKeyCallback(window, onKey);
    glfwSetCharCallback(window, onChar);
    glfwSetMouseButtonCallback(window, onMouseButton);
    glfwSetCursorPosCallback(window, onCursorPos);
    glfwSetScrollCallback(window, onScroll);
    glfwSetWindowFocusCallback(window, onFocus);
    glfwSetCursorEnterCallback(window, onCursorEnter);
    return host;
}

HostWindow::~HostWindow() {
    if (!impl_->window) return;
    glfwMakeContextCurrent(impl_->window);
    for (unsigned name : impl_->images) {
        const GLuint n = name;
        glDeleteTextures(1, &n);
    }
    if (impl_->imgui_gl) ImGui_ImplOpenGL2_Shutdown();
    if (impl_->imgui_glfw) ImGui_ImplGlfw_Shutdown();
    if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
    // GL objects are released while the context is still current.
    viewer_ = nullptr;
    glfwDestroyWindow(impl_->window);
    glfwTerminate();
    g_window_alive = false;
}

bool HostWindow::beginFrame() {
    Impl& impl = *impl_;
    impl.frame_start = Clock::now();
    impl.frame_start_cpu = threadCpuMs();
    glfwPollEvents();

    int w = 0, h = 0;
    glfwGetFramebufferSize(impl.window, &w, &h);
    if ((w != width_ || h != height_) && w > 0 && h > 0) {
        width_ = w;
        height_ = h;
        impl.embedded->resized(0, 0, w, h);
        impl.embedded->getEventQueue()->windowResize(0, 0, w, h);
    }

    ImGui_ImplOpenGL2_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    impl.applyInjectedToImGui();
    ImGui::NewFrame();

    // ImGui has seen everything; the rest goes where ImGui does not want it.
    const ImGuiIO& io = ImGui::GetIO();
    routed_.clear();
    auto routeAll = [&](const std::vector<InputEvent>& events) {
        for (const InputEvent& e : events) {
            if (!impl.router.route(e, io.WantCaptureMouse, io.WantCaptureKeyboard)) continue;
            routed_.push_back(e);
            forwardToOsg(e, *impl.embedded->getEventQueue());
        }
    };
    routeAll(impl.pending);
    routeAll(impl.injected);
    impl.pending.clear();
    impl.injected.clear();

    impl.app_start = Clock::now();
    impl.events_ms = msBetween(impl.frame_start, impl.app_start);
    return !closeRequested();
}

bool HostWindow::keyDown(int key) const { return impl_->router.keyDown(key); }
bool HostWindow::mouseDown(int button) const { return impl_->router.mouseDown(button); }

FrameTiming HostWindow::endFrame(double simulation_time_s) {
    Impl& impl = *impl_;
    FrameTiming t;
    t.events_ms = impl.events_ms;
    auto mark = Clock::now();
    t.app_ms = msBetween(impl.app_start, mark);

    osgViewer::Viewer& viewer = *viewer_;
    if (impl.first_frame) {
        viewer.init();
        impl.first_frame = false;
    }
    viewer.advance(simulation_time_s < 0.0 ? USE_REFERENCE_TIME : simulation_time_s);
    viewer.eventTraversal();
    viewer.updateTraversal();
    const auto render_start = Clock::now();
    t.update_ms = msBetween(mark, render_start);

    impl.draw_start = Clock::time_point{};
    viewer.renderingTraversals();
    mark = Clock::now();
    const bool drew = impl.draw_start != Clock::time_point{};
    t.cull_ms = msBetween(render_start, drew ? impl.draw_start : mark);
    t.draw_ms = drew ? msBetween(impl.draw_start, mark) : 0.0;
    t.draw_cpu_ms = drew ? processCpuMs() - impl.draw_start_cpu : 0.0;

    auto screenshot = [&] {
        const auto s0 = Clock::now();
        screenshot_status_ = writeScreenshot(width_, height_, impl.screenshot_path);
        impl.screenshot_path.clear();
        t.screenshot_ms += msBetween(s0, Clock::now());
    };
    auto capture = [&] {
        const auto s0 = Clock::now();
        impl.capture->readPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE);
        impl.capture = nullptr;
        t.screenshot_ms += msBetween(s0, Clock::now());
    };
    if (!impl.screenshot_path.empty() && !impl.screenshot_with_overlay) screenshot();
    if (impl.capture && !impl.capture_with_overlay) capture();

    const auto overlay_start = Clock::now();
    drawImGuiOverOsg(*impl.embedded->getState(), impl.uploads, impl.doomed);
    if (options_.finish_gl_for_timing) glFinish();
    t.overlay_ms = msBetween(overlay_start, Clock::now());

    if (!impl.screenshot_path.empty()) screenshot();
    if (impl.capture) capture();

    const auto swap_start = Clock::now();
    glfwSwapBuffers(impl.window);
    const auto end = Clock::now();
    t.swap_ms = msBetween(swap_start, end);
    t.frame_ms = msBetween(impl.frame_start, end);
    t.main_cpu_ms = threadCpuMs() - impl.frame_start_cpu;
    if (impl.frames_left > 0 && --impl.frames_left == 0) impl.close_requested = true;
    return t;
}

void HostWindow::requestClose() { impl_->close_requested = true; }
bool HostWindow::closeRequested() const { return impl_->close_requested || glfwWindowShouldClose(impl_->window); }

void HostWindow::requestScreenshot(const std::string& png_path, bool with_overlay) {
    impl_->screenshot_path = png_path;
    impl_->screenshot_with_overlay = with_overlay;
}

void HostWindow::requestCapture(osg::Image* image, bool with_overlay) {
    impl_->capture = image;
    impl_->capture_with_overlay = with_overlay;
}

ImTextureID HostWindow::uploadImage(const std::vector<uint8_t>& rgba, int width, int height, ImTextureID previous) {
    TERRASYNTH_REQUIRE(width > 0 && height > 0 && rgba.size() == static_cast<size_t>(width) * height * 4,
                       "an image is width x height RGBA8 pixels");
    Impl& impl = *impl_;
    auto name = static_cast<unsigned>(reinterpret_cast<uintptr_t>(previous));
    if (std::find(impl.images.begin(), impl.images.end(), name) == impl.images.end()) {
        name = newImageTexture();
        impl.images.push_back(name);
    }
    impl.uploads.push_back({name, width, height, rgba});
    return reinterpret_cast<ImTextureID>(static_cast<uintptr_t>(name));
}

void HostWindow::releaseImage(ImTextureID image) {
    Impl& impl = *impl_;
    const auto name = static_cast<unsigned>(reinterpret_cast<uintptr_t>(image));
    auto it = std::find(impl.images.begin(), impl.images.end(), name);
    if (it == impl.images.end()) return;
    impl.images.erase(it);
    impl.uploads.erase(std::remove_if(impl.uploads.begin(), impl.uploads.end(),
                                      [name](const ImageUpload& u) { return u.texture == name; }),
                       impl.uploads.end());
    impl.doomed.push_back(name);
}

namespace {
InputEvent injectedEvent(InputEvent::Type type) {
    InputEvent e;
    e.type = type;
    e.injected = true;
    return e;
}
}  // namespace

void HostWindow::injectKey(int key, bool pressed, int mods) {
    InputEvent e = injectedEvent(pressed ? InputEvent::Type::KeyDown : InputEvent::Type::KeyUp);
    e.key = key;
    e.mods = mods;
    impl_->injected.push_back(e);
}

void HostWindow::injectChar(uint32_t codepoint) {
    InputEvent e = injectedEvent(InputEvent::Type::Char);
    e.codepoint = codepoint;
    impl_->injected.push_back(e);
}

void HostWindow::injectMouseMove(double x, double y) {
    InputEvent e = injectedEvent(InputEvent::Type::MouseMove);
    e.x = x;
    e.y = y;
    impl_->injected.push_back(e);
}

void HostWindow::injectMouseButton(int button, bool pressed, int mods) {
    InputEvent e = injectedEvent(pressed ? InputEvent::Type::MouseDown : InputEvent::Type::MouseUp);
    e.button = button;
    e.mods = mods;
    // At the script's last pointer position (the real cursor's if the script never moved it).
    if (impl_->mouse_injected) {
        e.x = impl_->mouse_x;
        e.y = impl_->mouse_y;
    } else {
        glfwGetCursorPos(impl_->window, &e.x, &e.y);
    }
    for (auto it = impl_->injected.rbegin(); it != impl_->injected.rend(); ++it)
        if (it->type == InputEvent::Type::MouseMove) {
            e.x = it->x;
            e.y = it->y;
            break;
        }
    impl_->injected.push_back(e);
}

void HostWindow::injectScroll(double dx, double dy) {
    InputEvent e = injectedEvent(InputEvent::Type::Scroll);
    e.scroll_x = dx;
    e.scroll_y = dy;
    e.x = impl_->mouse_x;
    e.y = impl_->mouse_y;
    impl_->injected.push_back(e);
}

}  // namespace terrasynth::host
