// Shared by the tests that render with osgViewer into a window under Xvfb (header-only, so only
// those tests pull in osgViewer): a single-threaded viewer on its own window, and a read-back of
// every drawn frame.
#pragma once

#include <cstdlib>
#include <string>

#include <osg/Camera>
#include <osg/GraphicsContext>
#include <osg/Image>
#include <osgViewer/Viewer>

namespace terrasynth::test {

// Reads the viewport back (GL_RGB, row 0 at the bottom) at the end of every draw.
struct Capture : osg::Camera::DrawCallback {
    int width, height;
    osg::ref_ptr<osg::Image> image = new osg::Image;
    Capture(int w, int h) : width(w), height(h) {}
    void operator()(osg::RenderInfo&) const override { image->readPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE); }
};

// Puts `viewer` single-threaded on a new undecorated width x height window, perspective `fovy_deg`,
// clearing to `clear`, with `capture` as the final draw callback, and realizes it. Returns "" or why
// no window could be made.
inline std::string setUpWindowViewer(osgViewer::Viewer& viewer, int width, int height, const osg::Vec4& clear,
                                     double fovy_deg, Capture* capture) {
    osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
    traits->readDISPLAY();
    traits->setUndefinedScreenDetailsToDefaultScreen();
    traits->width = width;
    traits->height = height;
    traits->windowDecoration = false;
    traits->doubleBuffer = true;
    osg::ref_ptr<osg::GraphicsContext> gc = osg::GraphicsContext::createGraphicsContext(traits.get());
    if (!gc.valid()) {
        const char* display = std::getenv("DISPLAY");
        return std::string("no graphics context (DISPLAY=") + (display ? display : "") + ")";
    }
    viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    osg::Camera* cam = viewer.getCamera();
    cam->setGraphicsContext(gc.get());
    cam->setViewport(0, 0, width, height);
    cam->setProjectionMatrixAsPerspective(fovy_deg, double(width) / height, 1.0, 1e6);
    cam->setClearColor(clear);
    cam->setFinalDrawCallback(capture);
    viewer.realize();
    return viewer.isRealized() ? "" : "the viewer could not be realized";
}

}  // namespace terrasynth::test
