// EditorCamera (free orbit and aerial views), ScreenProjection and terrain picking.
#include "terrasynth_editor/editor_camera.h"

#include <algorithm>
#include <cmath>

#include <osgGA/GUIEventAdapter>

namespace terrasynth::editor {
namespace {
constexpr double kMinPitch = 5.0, kMaxPitch = 89.0;
constexpr double kTurnDegPerPixel = 0.3;
constexpr double kZoomPerStep = 1.15;
}  // namespace

EditorCamera::EditorCamera(double fovy_deg, double aspect) : fovy_deg_(fovy_deg), aspect_(aspect) {}

void EditorCamera::setFree(const osg::Vec3d& center, double distance_m, double heading_deg, double pitch_deg) {
    mode_ = Mode::Free;
    center_ = center;
    distance_ = std::max(distance_m, 1.0);
    heading_deg_ = std::fmod(heading_deg, 360.0);
    pitch_deg_ = std::clamp(pitch_deg, kMinPitch, kMaxPitch);
}

void EditorCamera::setAerial(const osg::Vec3d& center, double width_m) {
    mode_ = Mode::Aerial;
    center_ = center;
    heading_deg_ = 0.0;
    pitch_deg_ = 90.0;
    const double half_tan = aspect_ * std::tan(osg::DegreesToRadians(0.5 * fovy_deg_));
    distance_ = std::max(0.5 * width_m / half_tan, 1.0);
}

double EditorCamera::viewWidthM() const {
    return 2.0 * distance_ * aspect_ * std::tan(osg::DegreesToRadians(0.5 * fovy_deg_));
}

osg::Vec3d EditorCamera::eye() const {
    if (mode_ == Mode::Aerial) return center_ + osg::Vec3d(0.0, 0.0, distance_);
    const double h = osg::DegreesToRadians(heading_deg_), p = osg::DegreesToRadians(pitch_deg_);
    // Looking towards heading h (clockwise from north): the eye is behind the centre.
    const osg::Vec3d forward(std::sin(h) * std::cos(p), std::cos(h) * std::cos(p), -std::sin(p));
    return center_ - forward * distance_;
}

osg::Matrixd EditorCamera::getInverseMatrix() const {
    const osg::Vec3d up = mode_ == Mode::Aerial ? osg::Vec3d(0.0, 1.0, 0.0) : osg::Vec3d(0.0, 0.0, 1.0);
    return osg::Matrixd::lookAt(eye(), center_, up);
}

osg::Matrixd EditorCamera::getMatrix() const { return osg::Matrixd::inverse(getInverseMatrix()); }

void EditorCamera::setByMatrix(const osg::Matrixd& matrix) {
    // Keep the distance; look along the matrix's -z from its eye.
    const osg::Vec3d eye_at = matrix.getTrans();
    osg::Vec3d forward = osg::Vec3d(0.0, 0.0, -1.0) * osg::Matrixd::rotate(matrix.getRotate());
    forward.normalize();
    center_ = eye_at + forward * distance_;
    heading_deg_ = osg::RadiansToDegrees(std::atan2(forward.x(), forward.y()));
    pitch_deg_ = std::clamp(osg::RadiansToDegrees(std::asin(std::clamp(-forward.z(), -1.0, 1.0))), kMinPitch, kMaxPitch);
    mode_ = Mode::Free;
}

void EditorCamera::dropCenterOnGround() {
    if (!ground_) return;
    if (auto z = ground_(center_.x(), center_.y())) center_.z() = *z;
}

void EditorCamera::pan(double dx_px, double dy_px, double window_height_px) {
    // Metres per pixel at the centre's distance.
    const double scale = 2.0 * distance_ * std::tan(osg::DegreesToRadians(0.5 * fovy_deg_)) / std::max(window_height_px, 1.0);
    const double h = osg::DegreesToRadians(heading_deg_);
    const osg::Vec3d right(std::cos(h), -std::sin(h), 0.0), ahead(std::sin(h), std::cos(h), 0.0);
    // Dragging moves the ground with the pointer: the centre moves the other way.
    center_ -= right * (dx_px * scale);
    center_ -= ahead * (dy_px * scale);
    dropCenterOnGround();
}

bool EditorCamera::handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter& aa) {
    using E = osgGA::GUIEventAdapter;
    // Window y grows up in osgGA's default mouse orientation; use top-left pixels like the host.
    const float x = ea.getX();
    const float y = ea.getMouseYOrientation() == E::Y_INCREASING_UPWARDS ? ea.getWindowHeight() - ea.getY() : ea.getY();
    switch (ea.getEventType()) {
        case E::PUSH: {
            const unsigned mask = ea.getButtonMask();
            // The left button belongs to the tools.
            if (mask & (E::RIGHT_MOUSE_BUTTON | E::MIDDLE_MOUSE_BUTTON)) {
                drag_button_ = static_cast<int>(mask);
                last_x_ = x, last_y_ = y;
                return true;
            }
            return false;
        }
        case E::DRAG: {
            if (!drag_button_) return false;
            const double dx = x - last_x_, dy = y - last_y_;
            last_x_ = x, last_y_ = y;
            const bool turn = (drag_button_ & E::RIGHT_MOUSE_BUTTON) && mode_ == Mode::Free;
            if (turn) {
                heading_deg_ = std::fmod(heading_deg_ + dx * kTurnDegPerPixel + 360.0, 360.0);
                pitch_deg_ = std::clamp(pitch_deg_ + dy * kTurnDegPerPixel, kMinPitch, kMaxPitch);
            } else {
                pan(dx, -dy, ea.getWindowHeight());
            }
            aa.requestRedraw();
            return true;
        }
        case E::RELEASE:
            if (ea.getButtonMask() == 0) drag_button_ = 0;
            return false;
        case E::SCROLL: {
            const bool in = ea.getScrollingMotion() == E::SCROLL_UP;
            distance_ = std::max(distance_ * (in ? 1.0 / kZoomPerStep : kZoomPerStep), 10.0);
            return true;
        }
        default:
            return false;
    }
}

ScreenProjection::ScreenProjection(const osg::Matrixd& view, const osg::Matrixd& projection, int width, int height)
    : width_(width), height_(height) {
    // Normalised device coordinates to window pixels with the origin at the top-left corner.
    const osg::Matrixd window = osg::Matrixd::translate(1.0, -1.0, 1.0) * osg::Matrixd::scale(0.5 * width, -0.5 * height, 0.5);
    to_window_ = view * projection * window;
    from_window_ = osg::Matrixd::inverse(to_window_);
}

ScreenProjection ScreenProjection::of(const osg::Camera& camera, int width, int height) {
    return ScreenProjection(camera.getViewMatrix(), camera.getProjectionMatrix(), width, height);
}

std::optional<osg::Vec2d> ScreenProjection::toScreen(const osg::Vec3d& world) const {
    // Homogeneous transform by hand to see w (behind the eye when w <= 0).
    const osg::Matrixd& m = to_window_;
    const double x = world.x(), y = world.y(), z = world.z();
    const double w = x * m(0, 3) + y * m(1, 3) + z * m(2, 3) + m(3, 3);
    if (w <= 1e-9) return std::nullopt;
    const double sx = (x * m(0, 0) + y * m(1, 0) + z * m(2, 0) + m(3, 0)) / w;
    const double sy = (x * m(0, 1) + y * m(1, 1) + z * m(2, 1) + m(3, 1)) / w;
    return osg::Vec2d(sx, sy);
}

void ScreenProjection::ray(double x, double y, osg::Vec3d* origin, osg::Vec3d* direction) const {
    const osg::Vec3d near_point = osg::Vec3d(x, y, 0.0) * from_window_;
    const osg::Vec3d far_point = osg::Vec3d(x, y, 1.0) * from_window_;
    osg::Vec3d d = far_point - near_point;
    d.normalize();
    *origin = near_point;
    *direction = d;
}

std::optional<osg::Vec3d> pickTerrain(const osg::Vec3d& origin, const osg::Vec3d& direction,
                                      const std::function<std::optional<float>(double, double)>& ground,
                                      double min_step_m, double max_distance_m) {
    auto above = [&](double t) -> std::optional<double> {
        const osg::Vec3d p = origin + direction * t;
        const auto h = ground(p.x(), p.y());
        if (!h) return std::nullopt;
        return p.z() - *h;
    };
    double t0 = 0.0;
    std::optional<double> a0 = above(t0);
    // The eye may be over a hole in the resident tiles: walk until the ray is over terrain.
    while (!a0 && t0 < max_distance_m) a0 = above(t0 += 50.0 * min_step_m);
    if (!a0 || *a0 <= 0.0) return std::nullopt;
    while (t0 < max_distance_m) {
        // Shallow rays over steep ground would jump peaks with big steps: a third of the clearance.
        const double step = std::max(min_step_m, *a0 / 3.0);
        const double t1 = t0 + step;
        const std::optional<double> a1 = above(t1);
        if (!a1) return std::nullopt;
        if (*a1 <= 0.0) {
            double lo = t0, hi = t1;
            while (hi - lo > 1e-3) {
                const double mid = 0.5 * (lo + hi);
                const std::optional<double> am = above(mid);
                if (am && *am > 0.0) lo = mid;
                else hi = mid;
            }
            return origin + direction * hi;
        }
        t0 = t1;
        a0 = a1;
    }
    return std::nullopt;
}

}  // namespace terrasynth::editor
