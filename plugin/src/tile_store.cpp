#include "tile_store.h"

#include <algorithm>

namespace terrasynth::plugin {
namespace {

// Takes over a finished build's data, node and what culling and accounting need to know of them.
void setContent(ResidentTile& tile, TileBuild&& build) {
    TERRASYNTH_REQUIRE(build.status && build.data && build.node, "only a successful build becomes resident");
    tile.bytes = build.bytes + build.data->bytes();
    tile.data = std::move(build.data);
    tile.node = std::move(build.node);
    tile.box = build.box;
    tile.triangles = build.triangles;
    tile.generation = build.generation;
}

}  // namespace

ResidentTile* TileStore::find(const TileKey& key) {
    auto it = tiles_.find(key);
    return it == tiles_.end() ? nullptr : &it->second;
}

const ResidentTile* TileStore::find(const TileKey& key) const {
    auto it = tiles_.find(key);
    return it == tiles_.end() ? nullptr : &it->second;
}

ResidentTile& TileStore::add(TileBuild&& build, unsigned frame) {
    const TileKey key = build.key;
    TERRASYNTH_REQUIRE(!tiles_.count(key), "the tile is already resident");
    ResidentTile& tile = tiles_[key];
    setContent(tile, std::move(build));
    tile.last_used_frame = frame;
    bytes_ += tile.bytes;
    return tile;
}

osg::ref_ptr<osg::Node> TileStore::replace(ResidentTile& tile, TileBuild&& build) {
    osg::ref_ptr<osg::Node> old = tile.node;
    bytes_ -= tile.bytes;
    setContent(tile, std::move(build));
    bytes_ += tile.bytes;
    return old;
}

osg::ref_ptr<osg::Node> TileStore::remove(const TileKey& key) {
    auto it = tiles_.find(key);
    TERRASYNTH_REQUIRE(it != tiles_.end(), "the tile is not resident");
    osg::ref_ptr<osg::Node> node = it->second.node;
    bytes_ -= it->second.bytes;
    tiles_.erase(it);
    return node;
}

std::vector<TileKey> tilesToEvict(const TileStore& store, size_t budget_bytes, unsigned protected_frame) {
    std::vector<TileKey> out;
    if (store.bytes() <= budget_bytes) return out;
    struct Candidate {
        unsigned used;
        TileKey key;
        size_t bytes;
    };
    std::vector<Candidate> candidates;
    store.forEach([&](const TileKey& key, const ResidentTile& tile) {
        if (tile.last_used_frame < protected_frame) candidates.push_back({tile.last_used_frame, key, tile.bytes});
    });
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        return a.used != b.used ? a.used < b.used : a.key.level < b.key.level;
    });
    size_t bytes = store.bytes();
    for (const Candidate& c : candidates) {
        if (bytes <= budget_bytes) break;
        out.push_back(c.key);
        bytes -= c.bytes;
    }
    return out;
}

}  // namespace terrasynth::plugin
