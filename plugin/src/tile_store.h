// tile_store.h: the resident tiles (osgEarth REX's TileNodeRegistry) and which of them to evict
// when they outgrow the memory budget (REX's Unloader).
//
// A resident tile is its data model (TileData), its render model (the detached OSG node a worker
// built) and the bookkeeping culling, merging and eviction need. The store keeps the key -> tile
// map and the bytes all of them hold; it does not touch the scene graph (TerrainNode attaches and
// detaches the nodes it hands over). Not thread-safe: TerrainNode guards it with its mutex.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include <osg/BoundingBox>
#include <osg/Node>
#include <osg/ref_ptr>

#include "terrasynth_plugin/tile_key.h"
#include "tile_builder.h"
#include "tile_data.h"

namespace terrasynth::plugin {

struct ResidentTile {
    std::shared_ptr<const TileData> data;  // what it was built from; never null
    osg::ref_ptr<osg::Node> node;          // what is drawn
    osg::BoundingBox box;                  // world frame, skirt included
    size_t bytes = 0;                      // the node's client-side arrays plus the data's samples
    size_t triangles = 0;
    uint64_t generation = 0;               // edit generation its heights were read at
    unsigned last_used_frame = 0;          // last frame whose cull drew it or kept it
    double drawn_distance = 0.0;           // from the camera when the last cull drew it (m)
    bool dirty = false;                    // an edit may have changed it: a rebuild is wanted
};

class TileStore {
public:
    ResidentTile* find(const TileKey& key);
    const ResidentTile* find(const TileKey& key) const;
    // Makes the tile of a successful build resident (it must not be yet), last used in `frame`.
    ResidentTile& add(TileBuild&& build, unsigned frame);
    // Gives a resident tile the content of its rebuild; returns the node it had.
    osg::ref_ptr<osg::Node> replace(ResidentTile& tile, TileBuild&& build);
    // Removes a resident tile; returns its node.
    osg::ref_ptr<osg::Node> remove(const TileKey& key);

    size_t size() const { return tiles_.size(); }
    size_t bytes() const { return bytes_; }
    template <class F>
    void forEach(F&& f) {
        for (auto& [key, tile] : tiles_) f(key, tile);
    }
    template <class F>
    void forEach(F&& f) const {
        for (const auto& [key, tile] : tiles_) f(key, tile);
    }

private:
    std::unordered_map<TileKey, ResidentTile, TileKeyHash> tiles_;
    size_t bytes_ = 0;
};

// The tiles to evict, in order, until `store` holds at most `budget_bytes`: least recently used
// first, among equals the finest (cheapest to rebuild, least coverage). Tiles last used in
// `protected_frame` (the last cull drew them or kept them for a refinement) never go, so a view that
// needs more than the budget overshoots it rather than showing holes.
std::vector<TileKey> tilesToEvict(const TileStore& store, size_t budget_bytes, unsigned protected_frame);

}  // namespace terrasynth::plugin
