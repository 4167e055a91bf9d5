// The game's own scene nodes besides the terrain: the aircraft and the rings. Built once on the main
// thread; positions are double-precision transforms so they hold anywhere in the unbounded world.
#pragma once

#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <osg/Group>
#include <osg/MatrixTransform>

#include "terrasynth_game/flight_model.h"
#include "terrasynth_game/rings.h"

namespace terrasynth::game {

// A small delta-wing aircraft, nose along +y, about 14 m long, unlit colours shaded once for the
// terrain look's fixed sun (sun_direction: world unit vector towards the sun).
osg::ref_ptr<osg::Node> makeAircraftModel(const osg::Vec3& sun_direction);
// The aircraft's world pose (heading, pitch, roll of `a`).
osg::Matrixd aircraftPose(const Aircraft& a);

// The rings in view: one transform per ring over a shared torus, recoloured when collected.
class RingNodes {
public:
    RingNodes();
    osg::Group* root() { return root_.get(); }
    // Shows exactly `rings` (adds new ones, drops the others); `collected` are drawn as taken.
    void sync(const std::vector<Ring>& rings, const std::unordered_set<uint64_t>& collected);

private:
    osg::ref_ptr<osg::Group> root_;
    osg::ref_ptr<osg::Node> open_, taken_;
    std::unordered_map<uint64_t, osg::ref_ptr<osg::MatrixTransform>> shown_;
    std::unordered_set<uint64_t> shown_taken_;
};

}  // namespace terrasynth::game
