// terrasynth_plugin/terrain_look.h: how the terrain is shaded, so relief reads at a glance.
//
// One small GLSL 1.20 program (terrain_shader.cpp; Debian's OSG is a GL2 build) on the TerrainNode,
// so stock osgviewer, the editor and the game all draw the same:
//  - a fixed sun (directional light in the world frame, not the viewer's headlight): slopes facing
//    it are bright, those facing away dark, from any viewpoint;
//  - hypsometric tints: vegetation on low ground, drier upland, bare alpine ground, snow above a
//    snow line (lower on slopes facing north, absent on slopes too steep to hold it);
//  - slope tints: rock on slopes steeper than rock_slope_deg;
//  - optionally a colour per painted terrain type (tiles must carry the type attribute: see
//    TerrainNode::setTypeSource), mixed over the tints;
//  - distance fog towards fog_colour, reaching 95% at fog_visibility_m (hides the draw radius edge).
// The geomorphing of terrain_shader.cpp lives in the same vertex shader. Values are uniforms on the
// node's StateSet: changing the look rebuilds nothing.
#pragma once

#include <array>
#include <cstdint>

#include <osg/StateSet>
#include <osg/Vec3>

namespace terrasynth::plugin {

struct TerrainLook {
    // Where the light comes from: azimuth clockwise from north, elevation above the horizon
    // (degrees). The default is the cartographic hillshade convention, north-west at 40 degrees.
    float sun_azimuth_deg = 315.0f;
    float sun_elevation_deg = 40.0f;
    float ambient = 0.38f;  // light on faces turned away from the sun, [0, 1]
    float diffuse = 0.80f;  // direct sunlight on a face turned to the sun, [0, 2]
    // Hypsometric tint heights (metres above sea level), increasing.
    float lowland_top_m = 1500.0f;   // vegetation below, blending into dry upland above
    float alpine_m = 3000.0f;        // bare alpine ground from here
    float snow_line_m = 4000.0f;     // snow from here (on slopes gentle enough to hold it)
    float rock_slope_deg = 38.0f;    // steeper ground shows rock
    // Fog: 95% at this distance from the eye (metres); 0 = no fog.
    float fog_visibility_m = 0.0f;
    osg::Vec3 fog_colour{0.70f, 0.77f, 0.86f};
    // Per-type colours (type id -> colour) mixed over the tints by type_colour_mix in [0, 1]; types
    // beyond the table or unknown (255) keep the tints.
    static constexpr int kTypeColours = 8;
    std::array<osg::Vec3, kTypeColours> type_colours{{{0.80f, 0.45f, 0.30f}, {0.30f, 0.55f, 0.80f},
                                                      {0.85f, 0.75f, 0.30f}, {0.45f, 0.75f, 0.40f},
                                                      {0.70f, 0.40f, 0.75f}, {0.35f, 0.75f, 0.75f},
                                                      {0.90f, 0.55f, 0.60f}, {0.60f, 0.60f, 0.35f}}};
    float type_colour_mix = 0.0f;
};

// A look whose tint heights spread over [min_height_m, max_height_m] (e.g. the project extent's
// height range): vegetation in the lowest 30%, bare ground from half way, snow over the top 30%.
TerrainLook lookForHeightRange(float min_height_m, float max_height_m);

// The world-frame unit vector towards the sun (x east, y north, z up).
osg::Vec3 sunDirection(const TerrainLook& look);

// Puts the terrain program (look + geomorphing) and default uniforms on `ss`: no morph until a
// cull sets ts_lod_k (so files written by osgconv draw unmorphed), the default look.
void installTerrainProgram(osg::StateSet& ss);
// Sets the look's uniforms on `ss` (which must hold the terrain program).
void applyLook(osg::StateSet& ss, const TerrainLook& look);

// Vertex attribute locations of the terrain program.
constexpr unsigned kCoarseHeightAttribute = 6;  // float: height on the parent tile's surface
constexpr unsigned kTypeAttribute = 7;          // float: terrain type id (255 = unknown)

}  // namespace terrasynth::plugin
