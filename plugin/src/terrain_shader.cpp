// The terrain program (GLSL 1.20, compatibility profile): geomorphing in the vertex shader, the
// look of terrain_look.h (fixed sun, hypsometric and slope tints, snow, type colours, fog) per
// fragment. Tiles are only translated (their vertices are relative to the tile corner, see
// tile_builder.h), so model-space normals and heights are the terrain frame's.
#include <algorithm>
#include <cmath>

#include <mutex>

#include <osg/Program>
#include <osg/Shader>
#include <osg/Uniform>
#include <osgUtil/RenderBin>

#include "terrasynth_plugin/terrain_look.h"

namespace terrasynth::plugin {
namespace {

// Geomorphing: a vertex of a level-k tile is blended towards its parent's surface over the last
// quarter of the distance range in which level k is drawn: the cull refines a level-(k+1) tile
// while its spacing s projects above the pixel error, i.e. nearer than s * ts_lod_k, so at that
// distance the vertex already sits on the parent's surface and the switch is seamless. Tiles
// without a parent have ts_parent_spacing = 0 and do not move.
const char* kVertexShader = R"(#version 120
attribute float ts_coarse_z;
attribute float ts_type;
uniform float ts_parent_spacing;
uniform float ts_lod_k;
varying vec3 ts_normal;
varying float ts_height;
varying float ts_distance;
varying float ts_type_id;
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
    ts_normal = gl_Normal;
    ts_height = v.z;
    ts_distance = length(ep.xyz);
    ts_type_id = ts_type;
}
)";

// Tints by height, then rock on steep slopes, then snow above a line that is lower on slopes facing
// north and absent where the slope is too steep to hold it; lit by the fixed sun; fogged.
const char* kFragmentShader = R"(#version 120
uniform vec3 ts_sun;
uniform vec2 ts_light;
uniform vec4 ts_tint_heights;
uniform float ts_rock_cos;
uniform vec4 ts_fog;
uniform vec3 ts_type_colors[8];
uniform float ts_type_mix;
varying vec3 ts_normal;
varying float ts_height;
varying float ts_distance;
varying float ts_type_id;
void main() {
    vec3 n = normalize(ts_normal);
    float h = ts_height;
    float band = ts_tint_heights.w;
    vec3 c = mix(vec3(0.29, 0.40, 0.19), vec3(0.56, 0.50, 0.33),
                 smoothstep(ts_tint_heights.x - band, ts_tint_heights.x + band, h));
    c = mix(c, vec3(0.53, 0.51, 0.48), smoothstep(ts_tint_heights.y - band, ts_tint_heights.y + band, h));
    c = mix(c, vec3(0.40, 0.37, 0.35), smoothstep(ts_rock_cos + 0.05, ts_rock_cos - 0.05, n.z));
    float snow_line = ts_tint_heights.z - 1.5 * band * n.y;
    float snow = smoothstep(snow_line - band, snow_line + band, h) * smoothstep(0.55, 0.75, n.z);
    c = mix(c, vec3(0.95, 0.96, 0.98), snow);
    int t = int(ts_type_id + 0.5);
    if (ts_type_mix > 0.0 && t >= 0 && t < 8) c = mix(c, ts_type_colors[t], ts_type_mix);
    c *= ts_light.x + ts_light.y * max(dot(n, ts_sun), 0.0);
    float fog = 1.0 - exp(-ts_fog.w * ts_distance);
    gl_FragColor = vec4(mix(c, ts_fog.rgb, fog), 1.0);
}
)";

template <class T>
void setUniform(osg::StateSet& ss, const char* name, osg::Uniform::Type type, const T& v) {
    osg::Uniform* u = ss.getOrCreateUniform(name, type);
    u->setDataVariance(osg::Object::DYNAMIC);  // the look may change while a frame is drawn
    u->set(v);
}

// Tiles are drawn nearest first: the depth test then rejects hidden fragments before they are
// shaded (early z), which is most of a software rasterizer's fill cost, and the order depends only
// on the camera (the default state sort follows heap addresses).
const char* kFrontToBackBin = "terrasynth_front_to_back";

void registerFrontToBackBin() {
    static std::once_flag once;
    std::call_once(once, [] {
        osgUtil::RenderBin::addRenderBinPrototype(kFrontToBackBin,
                                                  new osgUtil::RenderBin(osgUtil::RenderBin::SORT_FRONT_TO_BACK));
    });
}

}  // namespace

TerrainLook lookForHeightRange(float min_height_m, float max_height_m) {
    TerrainLook look;
    const float lo = std::min(min_height_m, max_height_m), range = std::max(std::fabs(max_height_m - min_height_m), 1.0f);
    look.lowland_top_m = lo + 0.30f * range;
    look.alpine_m = lo + 0.50f * range;
    look.snow_line_m = lo + 0.70f * range;
    return look;
}

osg::Vec3 sunDirection(const TerrainLook& look) {
    const double az = osg::DegreesToRadians(double(look.sun_azimuth_deg));
    const double el = osg::DegreesToRadians(double(look.sun_elevation_deg));
    // Azimuth clockwise from north: north is +y, east is +x.
    return osg::Vec3(static_cast<float>(std::sin(az) * std::cos(el)), static_cast<float>(std::cos(az) * std::cos(el)),
                     static_cast<float>(std::sin(el)));
}

void installTerrainProgram(osg::StateSet& ss) {
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->setName("terrasynth_terrain");
    program->addShader(new osg::Shader(osg::Shader::VERTEX, kVertexShader));
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, kFragmentShader));
    program->addBindAttribLocation("ts_coarse_z", kCoarseHeightAttribute);
    program->addBindAttribLocation("ts_type", kTypeAttribute);
    ss.setAttributeAndModes(program.get());
    registerFrontToBackBin();
    ss.setRenderBinDetails(0, kFrontToBackBin);
    // No morph by default: roots, and files written by osgconv (no cull sets ts_lod_k).
    ss.addUniform(new osg::Uniform("ts_parent_spacing", 0.0f));
    ss.addUniform(new osg::Uniform("ts_lod_k", 0.0f));
    applyLook(ss, TerrainLook{});
}

void applyLook(osg::StateSet& ss, const TerrainLook& look) {
    setUniform(ss, "ts_sun", osg::Uniform::FLOAT_VEC3, sunDirection(look));
    setUniform(ss, "ts_light", osg::Uniform::FLOAT_VEC2, osg::Vec2(look.ambient, look.diffuse));
    // Blend bands scale with the tint range so a low, flat world still shows its steps.
    const float band = std::max(25.0f, 0.06f * (look.snow_line_m - look.lowland_top_m));
    setUniform(ss, "ts_tint_heights", osg::Uniform::FLOAT_VEC4,
               osg::Vec4(look.lowland_top_m, look.alpine_m, look.snow_line_m, band));
    const double rock_cos = std::cos(osg::DegreesToRadians(double(look.rock_slope_deg)));
    setUniform(ss, "ts_rock_cos", osg::Uniform::FLOAT, static_cast<float>(rock_cos));
    // 95% fog at the visibility distance: exp(-k * v) = 0.05, k = ln(20) / v.
    const float density = look.fog_visibility_m > 0.0f ? static_cast<float>(std::log(20.0) / look.fog_visibility_m) : 0.0f;
    setUniform(ss, "ts_fog", osg::Uniform::FLOAT_VEC4, osg::Vec4(look.fog_colour, density));
    osg::Uniform* colours = ss.getOrCreateUniform("ts_type_colors", osg::Uniform::FLOAT_VEC3, TerrainLook::kTypeColours);
    colours->setDataVariance(osg::Object::DYNAMIC);
    for (int i = 0; i < TerrainLook::kTypeColours; ++i) colours->setElement(static_cast<unsigned>(i), look.type_colours[i]);
    setUniform(ss, "ts_type_mix", osg::Uniform::FLOAT, std::clamp(look.type_colour_mix, 0.0f, 1.0f));
}

}  // namespace terrasynth::plugin
