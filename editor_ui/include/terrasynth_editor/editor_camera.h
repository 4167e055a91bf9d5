// terrasynth_editor/editor_camera.h: the editor's views and the geometry between screen and world.
//
// EditorCamera is the osgGA manipulator the host's viewer drives with the input ImGui and the tools
// do not take: the free 3D view orbits a centre on the ground (right drag turns, middle drag pans,
// the wheel zooms), the aerial view looks straight down with north up (right or middle drag pans,
// the wheel zooms). The left button is the tools'. World frame: terrasynth/grid.h (x east, y north,
// z up, metres).
//
// ScreenProjection is one frame's camera as plain math: world points to window pixels (origin
// top-left, as ImGui and the host's events count them) and window pixels to rays, and
// pickTerrain() intersects a ray with the terrain as drawn (TerrainNode::heightAt).
#pragma once

#include <functional>
#include <optional>

#include <osg/Camera>
#include <osg/Matrixd>
#include <osg/Vec3d>
#include <osgGA/CameraManipulator>

namespace terrasynth::editor {

class EditorCamera : public osgGA::CameraManipulator {
public:
    enum class Mode { Free, Aerial };

    // `fovy_deg` and `aspect` of the viewer's camera (the aerial width needs them).
    EditorCamera(double fovy_deg, double aspect);

    // Orbit around (cx, cy, cz): eye `distance_m` away, looking towards heading (clockwise from
    // north) and `pitch_deg` below the horizontal (5..89).
    void setFree(const osg::Vec3d& center, double distance_m, double heading_deg, double pitch_deg);
    // Straight down on (cx, cy, cz), `width_m` of ground across the window at the centre's height.
    void setAerial(const osg::Vec3d& center, double width_m);
    void setAspect(double aspect) { aspect_ = aspect; }
    Mode mode() const { return mode_; }
    const osg::Vec3d& center() const { return center_; }
    double distance() const { return distance_; }
    double headingDeg() const { return heading_deg_; }
    double pitchDeg() const { return pitch_deg_; }
    // Ground width across the window at the centre's height (aerial: what setAerial was given).
    double viewWidthM() const;
    // Called when the centre moves, to put it back on the ground (null: keep its height).
    void setGroundHeight(std::function<std::optional<float>(double x, double y)> ground) { ground_ = std::move(ground); }

    // osgGA::CameraManipulator
    void setByMatrix(const osg::Matrixd& matrix) override;
    void setByInverseMatrix(const osg::Matrixd& matrix) override { setByMatrix(osg::Matrixd::inverse(matrix)); }
    osg::Matrixd getMatrix() const override;
    osg::Matrixd getInverseMatrix() const override;
    bool handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter& aa) override;
    void home(double) override {}
    void home(const osgGA::GUIEventAdapter&, osgGA::GUIActionAdapter&) override {}

private:
    osg::Vec3d eye() const;
    void pan(double dx_px, double dy_px, double window_height_px);
    void dropCenterOnGround();

    Mode mode_ = Mode::Free;
    osg::Vec3d center_;
    double distance_ = 1000.0, heading_deg_ = 0.0, pitch_deg_ = 35.0;
    double fovy_deg_, aspect_;
    std::function<std::optional<float>(double, double)> ground_;
    int drag_button_ = 0;  // osgGA button mask of the drag in progress (0: none)
    float last_x_ = 0.0f, last_y_ = 0.0f;
};

class ScreenProjection {
public:
    ScreenProjection() = default;
    // The camera's view and projection as the last frame drew them, over a width x height window.
    ScreenProjection(const osg::Matrixd& view, const osg::Matrixd& projection, int width, int height);
    static ScreenProjection of(const osg::Camera& camera, int width, int height);

    // Window pixel (origin top-left) of a world point; nullopt behind the eye.
    std::optional<osg::Vec2d> toScreen(const osg::Vec3d& world) const;
    // The ray through window pixel (x, y): origin at the eye, unit direction.
    void ray(double x, double y, osg::Vec3d* origin, osg::Vec3d* direction) const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    osg::Matrixd to_window_, from_window_;
    int width_ = 0, height_ = 0;
};

// First intersection of the ray with the surface z = ground(x, y) within `max_distance_m`: marched
// in steps that shrink with the height above the ground (at least `min_step_m`), then bisected to a
// millimetre. nullopt when the ray misses (or leaves the resident terrain).
std::optional<osg::Vec3d> pickTerrain(const osg::Vec3d& origin, const osg::Vec3d& direction,
                                      const std::function<std::optional<float>(double x, double y)>& ground,
                                      double min_step_m, double max_distance_m);

}  // namespace terrasynth::editor
