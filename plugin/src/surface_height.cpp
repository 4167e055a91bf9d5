// TerrainNode::heightAt: the drawn surface's height under a point, from a resident tile's vertices.
#include <algorithm>
#include <cmath>

#include "terrasynth/mesh.h"
#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::plugin {

std::optional<float> TerrainNode::heightAt(double wx, double wy, int* tile_level) const {
    osg::ref_ptr<const osg::Vec3Array> vertices;
    TileKey key;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (int level = options_.min_level; level <= options_.max_level && !vertices; ++level) {
            key = layout_.keyAt(wx, wy, level);
            auto it = tiles_.find(key);
            if (it != tiles_.end()) vertices = it->second.vertices;
        }
    }
    if (!vertices) return std::nullopt;

    // Grid vertices come first, row-major from the north-west corner (tile_builder.h).
    const int n = layout_.tile_size / options_.mesh_step + 1;
    if (vertices->size() < static_cast<size_t>(n) * n) return std::nullopt;
    const double step_m = layout_.spacing(key.level) * options_.mesh_step;
    const double u = (wx - layout_.westX(key)) / step_m, w = (layout_.northY(key) - wy) / step_m;
    const int i = std::clamp(static_cast<int>(std::floor(u)), 0, n - 2);
    const int j = std::clamp(static_cast<int>(std::floor(w)), 0, n - 2);
    auto vertex = [&](int col, int row) -> const osg::Vec3f& { return (*vertices)[static_cast<size_t>(row) * n + col]; };
    // A tile reordered for the vertex cache (optimize_order) has no grid layout to read.
    const osg::Vec3f& a = vertex(i, j);
    if (std::fabs(a.x() - i * step_m) > 0.25 * step_m || std::fabs(-a.y() - j * step_m) > 0.25 * step_m)
        return std::nullopt;
    const double fu = std::clamp(u - i, 0.0, 1.0), fw = std::clamp(w - j, 0.0, 1.0);
    if (tile_level) *tile_level = key.level;
    return static_cast<float>(
        heightOnGridCell(a.z(), vertex(i + 1, j).z(), vertex(i, j + 1).z(), vertex(i + 1, j + 1).z(), fu, fw));
}

}  // namespace terrasynth::plugin
