// TileMesh (plain data) to a detached, VBO-backed OSG subgraph.
#include <cstring>

#include <osg/Geometry>
#include <osg/MatrixTransform>

#include "tile_builder.h"

namespace terrasynth::plugin {

osg::ref_ptr<osg::Node> makeTileNode(const TileMesh& mesh, double origin_x, double origin_y, size_t* bytes,
                                     const std::vector<float>* parent_heights, double parent_spacing,
                                     const std::vector<float>* type_ids) {
    const size_t nv = mesh.vertexCount();
    osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array(static_cast<unsigned>(nv));
    osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array(static_cast<unsigned>(nv));
    // Vec3f is three packed floats, the same layout as the mesh arrays.
    static_assert(sizeof(osg::Vec3f) == 3 * sizeof(float), "osg::Vec3f must be packed");
    if (nv) {
        std::memcpy((*vertices)[0].ptr(), mesh.positions.data(), nv * sizeof(osg::Vec3f));
        std::memcpy((*normals)[0].ptr(), mesh.normals.data(), nv * sizeof(osg::Vec3f));
    }
    osg::ref_ptr<osg::DrawElementsUInt> triangles =
        new osg::DrawElementsUInt(GL_TRIANGLES, mesh.indices.begin(), mesh.indices.end());

    osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry;
    geometry->setUseDisplayList(false);
    geometry->setUseVertexBufferObjects(true);
    geometry->setVertexArray(vertices.get());
    geometry->setNormalArray(normals.get(), osg::Array::BIND_PER_VERTEX);
    geometry->addPrimitiveSet(triangles.get());
    geometry->setDataVariance(osg::Object::STATIC);
    size_t extra = 0;
    if (parent_heights) {
        TERRASYNTH_REQUIRE(parent_heights->size() == nv, "one parent height per vertex");
        geometry->setVertexAttribArray(kCoarseHeightAttribute,
                                       new osg::FloatArray(parent_heights->begin(), parent_heights->end()),
                                       osg::Array::BIND_PER_VERTEX);
        geometry->getOrCreateStateSet()->addUniform(
            new osg::Uniform("ts_parent_spacing", static_cast<float>(parent_spacing)));
        extra += nv * sizeof(float);
    }
    if (type_ids) {
        TERRASYNTH_REQUIRE(type_ids->size() == nv, "one type id per vertex");
        geometry->setVertexAttribArray(kTypeAttribute, new osg::FloatArray(type_ids->begin(), type_ids->end()),
                                       osg::Array::BIND_PER_VERTEX);
        extra += nv * sizeof(float);
    }

    osg::ref_ptr<osg::MatrixTransform> transform = new osg::MatrixTransform(osg::Matrix::translate(origin_x, origin_y, 0.0));
    transform->setDataVariance(osg::Object::STATIC);
    transform->addChild(geometry.get());
    // Bounds now, on the worker, rather than lazily during the first cull.
    transform->getBound();
    if (bytes) *bytes = nv * 2 * sizeof(osg::Vec3f) + mesh.indices.size() * sizeof(uint32_t) + extra;
    return transform;
}

}  // namespace terrasynth::plugin
