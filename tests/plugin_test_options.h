// Small-tile TerrainNode options the plugin tests share: 64-sample tiles, 5 levels, 2 workers, a
// 4-pixel screen error, so a test's terrain pages quickly and still has several LODs.
#pragma once

#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::plugin {

inline TerrainNodeOptions smallTiles() {
    TerrainNodeOptions o;
    o.tile_size = 64;
    o.max_level = 4;
    o.threads = 2;
    o.pixel_error = 4.0f;
    return o;
}

}  // namespace terrasynth::plugin
