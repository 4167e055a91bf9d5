// headless_view.h: UPDATE + CULL of a scene without any graphics context (tests and benchmarks).
//
// Drives a scene such as a plugin::TerrainNode exactly as a viewer's frame loop does (update
// traversal, then cull with a perspective camera), minus the draw: for tests and benchmarks of tile
// selection, paging, merge budgets and memory that must run where there is no display. Not
// thread-safe; one per thread.
#pragma once

#include <osg/FrameStamp>
#include <osg/Node>
#include <osg/ref_ptr>
#include <osgUtil/SceneView>

namespace terrasynth::test {

class HeadlessView {
public:
    HeadlessView(osg::Node* scene, int width = 1280, int height = 720, double fovy_deg = 30.0);
    // One frame with the eye at `eye` looking at `center` (z up): UPDATE then CULL.
    void frame(const osg::Vec3d& eye, const osg::Vec3d& center);
    unsigned frameNumber() const { return frame_number_; }

private:
    osg::ref_ptr<osgUtil::SceneView> view_;
    osg::ref_ptr<osg::FrameStamp> stamp_;
    unsigned frame_number_ = 0;
};

}  // namespace terrasynth::test
