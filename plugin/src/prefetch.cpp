// Building tiles ahead of the camera: prefetch requests and the distances at which levels are drawn.
// planBuilds (tile_merge.cpp) queues the requests after everything the cull wants.
#include "terrasynth_plugin/terrain_node.h"

#include <algorithm>

#include "tile_store.h"

namespace terrasynth::plugin {

void TerrainNode::prefetch(const PixelWindow& region, int level) {
    TERRASYNTH_REQUIRE(level >= 0, "prefetch level must be >= 0");
    if (level < options_.min_level || level > options_.max_level) return;
    std::lock_guard<std::mutex> lock(mutex_);
    const unsigned frame = cull_frame_ == ~0u ? 0 : cull_frame_;
    for (const TileKey& key : tilesCovering(region, level)) {
        ResidentTile* tile = store_->find(key);
        if (tile && !tile->dirty) {
            tile->last_used_frame = std::max(tile->last_used_frame, frame);  // still wanted: keep it
            continue;
        }
        prefetch_[key] = frame;
    }
}

double TerrainNode::refinementDistance(int level) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pixels_per_meter_at_1m_ <= 0.0) return 0.0;
    if (level >= options_.max_level) return options_.view_radius_m;
    // selectTile refines a level-(k+1) tile while spacing(k+1) * pixels_per_meter(d) > pixel_error,
    // and pixels_per_meter(d) = pixels_per_meter(1 m) / d.
    return layout_.spacing(level + 1) * pixels_per_meter_at_1m_ / options_.pixel_error;
}

}  // namespace terrasynth::plugin
