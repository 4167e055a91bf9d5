// TerrainNode::heightAt: the drawn surface's height under a point, from the finest resident tile's
// data (tile_data.h), whatever order its render geometry keeps its vertices in.
#include "terrasynth_plugin/terrain_node.h"
#include "tile_store.h"

namespace terrasynth::plugin {

std::optional<float> TerrainNode::heightAt(double wx, double wy, int* tile_level) const {
    std::shared_ptr<const TileData> data;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (int level = options_.min_level; level <= options_.max_level && !data; ++level)
            if (const ResidentTile* tile = store_->find(layout_.keyAt(wx, wy, level))) data = tile->data;
    }
    if (!data) return std::nullopt;
    if (tile_level) *tile_level = data->key.level;
    return surfaceHeight(*data, wx, wy);
}

}  // namespace terrasynth::plugin
