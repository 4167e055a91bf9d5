#include "terrasynth_host/hole_check.h"

#include <cmath>
#include <cstdlib>

namespace terrasynth::host {

HoleCount countHoles(const osg::Image& image, const osg::Camera& camera, double ground_z, double radius_m,
                     const osg::Vec4& clear_colour, int tolerance) {
    HoleCount count;
    const osg::Viewport* viewport = camera.getViewport();
    if (!viewport || image.getPixelFormat() != GL_RGB || image.getDataType() != GL_UNSIGNED_BYTE) return count;
    const osg::Matrixd to_window = camera.getViewMatrix() * camera.getProjectionMatrix() * viewport->computeWindowMatrix();
    const osg::Matrixd from_window = osg::Matrixd::inverse(to_window);
    const osg::Vec3d eye = osg::Vec3d(0, 0, 0) * camera.getInverseViewMatrix();
    const int clear[3] = {static_cast<int>(std::lround(clear_colour.r() * 255)),
                          static_cast<int>(std::lround(clear_colour.g() * 255)),
                          static_cast<int>(std::lround(clear_colour.b() * 255))};
    const int width = std::min(image.s(), static_cast<int>(viewport->width()));
    const int height = std::min(image.t(), static_cast<int>(viewport->height()));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const osg::Vec3d a = osg::Vec3d(x + 0.5, y + 0.5, 0.0) * from_window;
            const osg::Vec3d b = osg::Vec3d(x + 0.5, y + 0.5, 1.0) * from_window;
            const osg::Vec3d dir = b - a;
            const unsigned char* p = image.data(x, y);
            const bool is_clear = std::abs(p[0] - clear[0]) <= tolerance && std::abs(p[1] - clear[1]) <= tolerance &&
                                  std::abs(p[2] - clear[2]) <= tolerance;
            if (dir.z() >= -1e-9) {
                count.sky_clear += is_clear;
                continue;
            }
            const double t = (ground_z - eye.z()) / dir.z();
            const osg::Vec3d hit = eye + dir * t;
            if (t < 0.0 || std::hypot(hit.x() - eye.x(), hit.y() - eye.y()) > radius_m) continue;
            ++count.required;
            count.holes += is_clear;
        }
    }
    return count;
}

}  // namespace terrasynth::host
