#include "scene_models.h"

#include <cmath>

#include <osg/Geometry>
#include <osg/StateSet>

namespace terrasynth::game {
namespace {

// Unlit triangles with one colour per triangle, shaded by the fixed sun so the model reads in 3D.
class ShadedMesh {
public:
    explicit ShadedMesh(const osg::Vec3& sun) : sun_(sun) {}
    void triangle(const osg::Vec3& a, const osg::Vec3& b, const osg::Vec3& c, const osg::Vec3& colour) {
        osg::Vec3 n = (b - a) ^ (c - a);
        n.normalize();
        const float light = 0.45f + 0.55f * std::fabs(n * sun_);  // both faces lit: thin parts
        for (const osg::Vec3& v : {a, b, c}) {
            vertices_->push_back(v);
            colours_->push_back(osg::Vec4(colour * light, 1.0f));
        }
    }
    osg::ref_ptr<osg::Geometry> build() {
        osg::ref_ptr<osg::Geometry> g = new osg::Geometry;
        g->setVertexArray(vertices_.get());
        g->setColorArray(colours_.get(), osg::Array::BIND_PER_VERTEX);
        g->addPrimitiveSet(new osg::DrawArrays(GL_TRIANGLES, 0, static_cast<int>(vertices_->size())));
        g->setUseDisplayList(false);
        g->setUseVertexBufferObjects(true);
        g->getOrCreateStateSet()->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
        return g;
    }

private:
    osg::Vec3 sun_;
    osg::ref_ptr<osg::Vec3Array> vertices_ = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec4Array> colours_ = new osg::Vec4Array;
};

// A torus around the y axis: the ring's axis is its facing direction.
osg::ref_ptr<osg::Node> makeTorus(double major, double minor, const osg::Vec3& colour) {
    ShadedMesh mesh(osg::Vec3(-0.5f, 0.5f, 0.7f));
    constexpr int kAround = 40, kTube = 8;
    auto point = [&](int i, int j) {
        const double u = 2.0 * M_PI * i / kAround, v = 2.0 * M_PI * j / kTube;
        const double r = major + minor * std::cos(v);
        return osg::Vec3(static_cast<float>(r * std::cos(u)), static_cast<float>(minor * std::sin(v)),
                         static_cast<float>(r * std::sin(u)));
    };
    for (int i = 0; i < kAround; ++i)
        for (int j = 0; j < kTube; ++j) {
            const osg::Vec3 a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
            mesh.triangle(a, b, c, colour);
            mesh.triangle(a, c, d, colour);
        }
    return mesh.build();
}

}  // namespace

osg::ref_ptr<osg::Node> makeAircraftModel(const osg::Vec3& sun) {
    ShadedMesh m(sun);
    const osg::Vec3 body(0.85f, 0.86f, 0.90f), wing(0.75f, 0.20f, 0.15f), canopy(0.15f, 0.25f, 0.40f);
    const osg::Vec3 nose(0, 8, 0), tail(0, -6, 0.3f), top(0, -1, 1.3f), belly(0, -1, -0.8f);
    const osg::Vec3 left(-1.1f, -1, 0), right(1.1f, -1, 0);
    // Fuselage: a double pyramid from the nose to the tail.
    for (const auto& [a, b] : {std::pair{top, right}, std::pair{right, belly}, std::pair{belly, left}, std::pair{left, top}}) {
        m.triangle(nose, b, a, body);
        m.triangle(tail, a, b, body);
    }
    m.triangle(osg::Vec3(0, 4, 0.4f), osg::Vec3(0.5f, 1, 0.9f), osg::Vec3(-0.5f, 1, 0.9f), canopy);
    // Delta wings and the fin.
    m.triangle(osg::Vec3(0, 3, 0), osg::Vec3(-7, -4.5f, 0), osg::Vec3(0, -4.5f, 0), wing);
    m.triangle(osg::Vec3(0, 3, 0), osg::Vec3(0, -4.5f, 0), osg::Vec3(7, -4.5f, 0), wing);
    m.triangle(osg::Vec3(0, -2, 0.5f), osg::Vec3(0, -6, 0.4f), osg::Vec3(0, -5.5f, 3.5f), wing);
    return m.build();
}

osg::Matrixd aircraftPose(const Aircraft& a) {
    // Row vectors: roll about the nose (+y), then pitch about the right wing (+x), then the heading
    // (clockwise from north, so about -z), then the position.
    return osg::Matrixd::rotate(a.roll, osg::Vec3d(0, 1, 0)) * osg::Matrixd::rotate(a.pitch, osg::Vec3d(1, 0, 0)) *
           osg::Matrixd::rotate(-a.heading, osg::Vec3d(0, 0, 1)) * osg::Matrixd::translate(a.x, a.y, a.z);
}

RingNodes::RingNodes()
    : root_(new osg::Group), open_(makeTorus(70.0, 5.0, osg::Vec3(1.0f, 0.62f, 0.12f))),
      taken_(makeTorus(70.0, 3.0, osg::Vec3(0.35f, 0.85f, 0.35f))) {}

void RingNodes::sync(const std::vector<Ring>& rings, const std::unordered_set<uint64_t>& collected) {
    std::unordered_set<uint64_t> wanted;
    for (const Ring& r : rings) {
        wanted.insert(r.id);
        const bool taken = collected.count(r.id) > 0;
        auto it = shown_.find(r.id);
        if (it == shown_.end()) {
            osg::ref_ptr<osg::MatrixTransform> t = new osg::MatrixTransform(
                osg::Matrixd::scale(r.radius_m / 70.0, r.radius_m / 70.0, r.radius_m / 70.0) *
                osg::Matrixd::rotate(-r.facing, osg::Vec3d(0, 0, 1)) * osg::Matrixd::translate(r.x, r.y, r.z));
            t->addChild(taken ? taken_.get() : open_.get());
            root_->addChild(t.get());
            it = shown_.emplace(r.id, t).first;
            if (taken) shown_taken_.insert(r.id);
        } else if (taken && !shown_taken_.count(r.id)) {
            it->second->replaceChild(open_.get(), taken_.get());
            shown_taken_.insert(r.id);
        }
    }
    for (auto it = shown_.begin(); it != shown_.end();) {
        if (wanted.count(it->first)) {
            ++it;
            continue;
        }
        root_->removeChild(it->second.get());
        shown_taken_.erase(it->first);
        it = shown_.erase(it);
    }
}

}  // namespace terrasynth::game
