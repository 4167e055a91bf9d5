#include "headless_view.h"

#include <osg/State>

namespace terrasynth::test {

HeadlessView::HeadlessView(osg::Node* scene, int width, int height, double fovy_deg)
    : view_(new osgUtil::SceneView), stamp_(new osg::FrameStamp) {
    view_->setDefaults();
    view_->setSceneData(scene);
    view_->setViewport(0, 0, width, height);
    // Near/far are recomputed from what is culled, as in a viewer.
    view_->setProjectionMatrixAsPerspective(fovy_deg, double(width) / height, 1.0, 1e7);
    view_->setFrameStamp(stamp_.get());
    // A State is needed for bookkeeping only; cull issues no GL calls.
    view_->setState(new osg::State);
}

void HeadlessView::frame(const osg::Vec3d& eye, const osg::Vec3d& center) {
    stamp_->setFrameNumber(frame_number_);
    stamp_->setReferenceTime(frame_number_ / 60.0);
    stamp_->setSimulationTime(frame_number_ / 60.0);
    view_->setViewMatrixAsLookAt(eye, center, osg::Vec3d(0, 0, 1));
    view_->update();
    view_->cull();
    ++frame_number_;
}

}  // namespace terrasynth::test
