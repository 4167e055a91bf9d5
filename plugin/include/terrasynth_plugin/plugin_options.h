// terrasynth_plugin/plugin_options.h: the osgDB option string of the .tsyn reader.
//
// Tokens "key=value" separated by spaces, commas or semicolons (osgconv -O "tileSize=128 seed=7"),
// keys case-insensitive:
//   tileSize=<8..2048>     quads per tile side (default 256)
//   maxLevel=<n>           level of the root tiles (default 5); minLevel=<n> finest drawn (default 0)
//   meshStep=<n>           grid step in samples, divides tileSize (default 1)
//   pixelError=<px>        refine while a sample spacing projects above this (default 8)
//   viewRadius=<m>         draw radius around the eye in metres (default: one root tile)
//   threads=<n>            worker threads (default: hardware threads)
//   cacheMB=<MiB>          resident tile budget (default 768)
//   mergesPerFrame=<n>, mergeBudgetMs=<ms>   UPDATE merge cap (defaults 16, 2 ms)
//   skirt=<spacings>       extra skirt depth in level spacings (default 2)
//   geomorph=0|1           blend tiles towards their parent before it takes over (default 1)
//   seed=<uint32>          overrides the project's synthesis seed
//   backend=opencl|reference, device=<substring>   synthesizer selection
//   preload=0|1            build the project extent synchronously before returning (default 1)
//   preloadLevel=<n>       level of that preload (default: the finest with at most 4x4 tiles)
//   sunAzimuth=<deg>, sunElevation=<deg>   where the fixed sun is (defaults 315, 40: north-west)
//   snowLine=<m>           snow above this height (default: from the project extent's heights)
//   fog=<m>                distance of 95% fog (default: 0.9 x the draw radius; 0 = none)
//   typeColors=0|1         colour each painted terrain type over the tints (default 0; costs a
//                          second synthesis per tile for the source map)
// Tokens without '=' or with unknown keys are other plugins' options and are ignored; a known key
// with a bad value is an error naming the key.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "terrasynth/status.h"
#include "terrasynth/synthesizer.h"
#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::plugin {

struct PluginOptions {
    TerrainNodeOptions node;
    std::optional<uint32_t> seed;
    SynthesizerOptions synthesizer;
    bool preload = true;
    int preload_level = -1;  // -1 = automatic
    bool max_level_given = false;  // maxLevel was in the string (else the reader may clamp it)
    std::optional<float> sun_azimuth_deg, sun_elevation_deg, snow_line_m, fog_m;
    bool type_colors = false;
};

Result<PluginOptions> parsePluginOptions(const std::string& option_string);

}  // namespace terrasynth::plugin
