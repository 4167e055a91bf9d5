// The geomorphing vertex shader (GLSL 1.20, compatibility profile: it reads OSG's fixed-function
// light and material state so the terrain is lit as without it).
#include <osg/Program>
#include <osg/Shader>
#include <osg/StateSet>
#include <osg/Uniform>

#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::plugin {
namespace {

// A vertex of a level-k tile is blended towards its parent's surface over the last quarter of the
// distance range in which level k is drawn: the cull refines a level-(k+1) tile while its spacing s
// projects above the pixel error, i.e. nearer than s * ts_lod_k, so at that distance the vertex
// already sits on the parent's surface and the switch is seamless. Tiles without a parent have
// ts_parent_spacing = 0 and do not move.
const char* kVertexShader = R"(#version 120
attribute float ts_coarse_z;
uniform float ts_parent_spacing;
uniform float ts_lod_k;
void main() {
    vec4 v = gl_Vertex;
    float handover = ts_parent_spacing * ts_lod_k;
    if (handover > 0.0) {
        float d = length((gl_ModelViewMatrix * v).xyz);
        float m = clamp((d - 0.75 * handover) / (0.25 * handover), 0.0, 1.0);
        v.z = mix(v.z, ts_coarse_z, m);
    }
    vec4 ep = gl_ModelViewMatrix * v;
    gl_Position = gl_ProjectionMatrix * ep;
    vec3 n = normalize(gl_NormalMatrix * gl_Normal);
    vec4 lp = gl_LightSource[0].position;
    vec3 l = normalize(lp.w == 0.0 ? lp.xyz : lp.xyz - ep.xyz);
    vec4 c = gl_FrontLightModelProduct.sceneColor + gl_FrontLightProduct[0].ambient +
             max(dot(n, l), 0.0) * gl_FrontLightProduct[0].diffuse;
    gl_FrontColor = vec4(c.rgb, 1.0);
    gl_BackColor = gl_FrontColor;
}
)";

const char* kFragmentShader = R"(#version 120
void main() { gl_FragColor = gl_Color; }
)";

}  // namespace

void installGeomorphProgram(osg::StateSet& ss) {
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->setName("terrasynth_geomorph");
    program->addShader(new osg::Shader(osg::Shader::VERTEX, kVertexShader));
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, kFragmentShader));
    program->addBindAttribLocation("ts_coarse_z", kCoarseHeightAttribute);
    ss.setAttributeAndModes(program.get());
    // Defaults: no morph (roots; and files written by osgconv, which have no cull to set ts_lod_k).
    ss.addUniform(new osg::Uniform("ts_parent_spacing", 0.0f));
    ss.addUniform(new osg::Uniform("ts_lod_k", 0.0f));
}

}  // namespace terrasynth::plugin
