// TerrainNode: construction, traversal dispatch, editing hooks, preload and statistics.
// The cull-time selection is in tile_selection.cpp, the UPDATE-time merge in tile_merge.cpp, the
// surface height in surface_height.cpp.
#include "terrasynth_plugin/terrain_node.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>

#include <osgUtil/CullVisitor>

#include "tile_loader.h"
#include "tile_store.h"

namespace terrasynth::plugin {

Status validateOptions(const TerrainNodeOptions& o) {
    auto bad = [](const std::string& name, const std::string& why) { return Status::error(name + ": " + why); };
    if (o.tile_size < 8 || o.tile_size > 2048) return bad("tileSize", "must be in [8, 2048]");
    if (o.min_level < 0 || o.min_level > 20) return bad("minLevel", "must be in [0, 20]");
    if (o.max_level < o.min_level || o.max_level > 20) return bad("maxLevel", "must be in [minLevel, 20]");
    if (o.mesh_step < 1 || o.tile_size % o.mesh_step != 0) return bad("meshStep", "must divide tileSize");
    if (!(o.pixel_error > 0.0f) || !std::isfinite(o.pixel_error)) return bad("pixelError", "must be finite and > 0");
    if (!(o.view_radius_m >= 0.0) || !std::isfinite(o.view_radius_m)) return bad("viewRadius", "must be finite and >= 0 (0 = one root tile)");
    if (o.threads < 0 || o.threads > 256) return bad("threads", "must be in [0, 256]");
    if (!(o.cache_mb > 0.0) || !std::isfinite(o.cache_mb)) return bad("cacheMB", "must be finite and > 0");
    if (o.max_merges_per_frame < 1) return bad("mergesPerFrame", "must be >= 1");
    if (!(o.merge_budget_ms > 0.0)) return bad("mergeBudgetMs", "must be > 0");
    if (!(o.skirt_extra_spacings >= 0.0f) || !std::isfinite(o.skirt_extra_spacings)) return bad("skirt", "must be finite and >= 0");
    if (o.geomorph && (o.tile_size / o.mesh_step) % 2 != 0)
        return bad("geomorph", "needs an even tileSize / meshStep");
    return Status::ok();
}

int clampedMaxLevel(const TerrainNodeOptions& o, int database_levels) {
    return std::max(o.min_level, std::min(o.max_level, database_levels - 1));
}

TerrainNode::TerrainNode(HeightSource source, double meters_per_pixel, const TerrainNodeOptions& options)
    : options_(options), source_(std::move(source)), store_(std::make_unique<TileStore>()) {
    const Status valid = validateOptions(options);
    TERRASYNTH_REQUIRE(valid.isOk(), valid.message().c_str());
    TERRASYNTH_REQUIRE(meters_per_pixel > 0.0, "meters_per_pixel must be positive");
    layout_.tile_size = options.tile_size;
    layout_.meters_per_pixel = meters_per_pixel;
    TileBuildSettings settings;
    settings.layout = layout_;
    settings.mesh_step = options.mesh_step;
    settings.skirt_extra_spacings = options.skirt_extra_spacings;
    settings.optimize_order = options.optimize_order;
    settings.geomorph = options.geomorph;
    settings.max_level = options.max_level;
    if (options_.view_radius_m <= 0.0) options_.view_radius_m = layout_.tileMeters(options_.max_level);
    const int threads = options.threads > 0 ? options.threads
                                            : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    loader_ = std::make_unique<TileLoader>(settings, threads);

    // Culling is ours (per tile); the node itself has no meaningful bound in an unbounded world.
    setCullingActive(false);
    // We need UPDATE traversals without an update callback (which users may want for themselves).
    setNumChildrenRequiringUpdateTraversal(getNumChildrenRequiringUpdateTraversal() + 1);

    // The look and the geomorphing are one program (terrain_shader.cpp); without geomorphing the
    // cull never sets ts_lod_k and nothing morphs.
    installTerrainProgram(*getOrCreateStateSet());
}

TerrainNode::~TerrainNode() { loader_.reset(); }

void TerrainNode::traverse(osg::NodeVisitor& nv) {
    switch (nv.getVisitorType()) {
        case osg::NodeVisitor::CULL_VISITOR:
            if (auto* cv = nv.asCullVisitor()) {
                cull(*cv);
                return;
            }
            break;
        case osg::NodeVisitor::UPDATE_VISITOR: {
            const osg::FrameStamp* fs = nv.getFrameStamp();
            update(fs ? fs->getFrameNumber() : frame_counter_++);
            return;  // tiles carry no callbacks
        }
        default:
            break;
    }
    // Generic visitors are mostly scene rewriters (osgviewer runs osgUtil::Optimizer on what it
    // loads: flattening the tile transforms would push world offsets into float vertices and merging
    // would fuse tiles the manager swaps and evicts), so the managed tiles are not theirs to see.
    if (nv.getVisitorType() == osg::NodeVisitor::NODE_VISITOR) return;
    // Intersection and other typed visitors see the children: the tiles drawn in the last frame, or
    // the last preload before the first frame — one consistent set of LODs.
    osg::Group::traverse(nv);
}

osg::BoundingSphere TerrainNode::computeBound() const {
    {
        std::lock_guard<std::mutex> lock(home_mutex_);
        if (home_bound_.valid()) return home_bound_;
    }
    osg::BoundingSphere bs = osg::Group::computeBound();
    if (bs.valid()) bs.expandBy(bs.center() + osg::Vec3(0.0f, 0.0f, 2.0f * bs.radius()));
    return bs;
}

void TerrainNode::setHomeExtent(const PixelWindow& extent) {
    TERRASYNTH_REQUIRE(!extent.empty(), "the home extent must not be empty");
    const auto range = heightRange(extent);
    const float low = range ? range->first : 0.0f, high = range ? range->second : 0.0f;
    const GridFrame frame = layout_.frame();
    const double width_m = extent.width * frame.spacing(0), height_m = extent.height * frame.spacing(0);
    const double size = std::max(width_m, height_m);
    const double cx = frame.worldX(extent.x + 0.5 * extent.width), cy = frame.worldY(extent.y + 0.5 * extent.height);
    // Manipulators put the eye at radius / sin(their camera's half fov) south of the centre, at its
    // height, looking north. The radius is chosen for stock osgviewer's half fov (14.6 degrees): the
    // eye lands 1.3 extents south of the extent's near edge (whose corners are then 21 degrees off
    // the axis, inside a 16:9 view), with the centre over the extent's middle; the height puts the
    // near edge 11 degrees below the horizontal (the far edge about 6), and above every peak. Wider
    // fields of view bring the eye closer and still show it all.
    const double viewer_half_fov = osg::DegreesToRadians(14.6), near_edge_down = osg::DegreesToRadians(11.0);
    const double near_distance = 1.3 * size;
    const double eye_distance = near_distance + 0.5 * height_m;
    const double eye_height = std::max(0.5 * (low + high) + near_distance * std::tan(near_edge_down),
                                       double(high) + 0.05 * size);
    std::lock_guard<std::mutex> lock(home_mutex_);
    home_bound_ = osg::BoundingSphere(osg::Vec3(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(eye_height)),
                                      static_cast<float>(eye_distance * std::sin(viewer_half_fov)));
    dirtyBound();
}

void TerrainNode::setLook(const TerrainLook& look) {
    std::lock_guard<std::mutex> lock(mutex_);
    look_ = look;
    applyLook(*getOrCreateStateSet(), look);
}

TerrainLook TerrainNode::look() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return look_;
}

void TerrainNode::setTypeSource(TypeSource types) {
    std::lock_guard<std::mutex> lock(mutex_);
    type_source_ = std::move(types);
}

std::vector<TileKey> TerrainNode::tilesCovering(const PixelWindow& region, int level) const {
    const int64_t span = static_cast<int64_t>(layout_.tile_size) << level;
    std::vector<TileKey> keys;
    if (region.empty()) return keys;
    for (int64_t ty = floorDiv(region.y, span); ty <= floorDiv(region.y + region.height - 1, span); ++ty)
        for (int64_t tx = floorDiv(region.x, span); tx <= floorDiv(region.x + region.width - 1, span); ++tx)
            keys.push_back({level, tx, ty});
    return keys;
}

std::optional<std::pair<float, float>> TerrainNode::heightRange(const PixelWindow& region) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (int level = options_.min_level; level <= options_.max_level; ++level) {
        std::optional<std::pair<float, float>> range;
        for (const TileKey& key : tilesCovering(region, level)) {
            const ResidentTile* tile = store_->find(key);
            if (!tile) continue;
            const TileData& data = *tile->data;
            if (!range) range = std::make_pair(data.min_height, data.max_height);
            range->first = std::min(range->first, data.min_height);
            range->second = std::max(range->second, data.max_height);
        }
        if (range) return range;
    }
    return std::nullopt;
}
bool TerrainNode::touches(const TileKey& key, const PixelWindow& r) const {
    const PixelWindow w = tileReadWindow(key, loader_->settings());
    // Level-k sample X reads level-0 pixels [X*2^k, (X+1)*2^k).
    const int64_t s = int64_t{1} << key.level;
    const int64_t x0 = w.x * s, y0 = w.y * s, x1 = (w.x + w.width) * s, y1 = (w.y + w.height) * s;
    return x0 < r.x + r.width && r.x < x1 && y0 < r.y + r.height && r.y < y1;
}

uint64_t TerrainNode::invalidate(const PixelWindow& region, int64_t margin_px) {
    const PixelWindow widened{region.x - margin_px, region.y - margin_px,
                              static_cast<int>(region.width + 2 * margin_px),
                              static_cast<int>(region.height + 2 * margin_px)};
    std::lock_guard<std::mutex> lock(mutex_);
    invalidateLocked({++generation_, widened, false});
    return generation_;
}

size_t TerrainNode::tilesAwaitingRebuild(uint64_t generation) const {
    std::lock_guard<std::mutex> lock(mutex_);
    size_t n = 0;
    for (const TileKey& key : drawn_keys_) {
        // A dirty tile built at or after `generation` already shows that edit (a later one marked it).
        const ResidentTile* tile = store_->find(key);
        n += tile && tile->dirty && tile->generation < generation;
    }
    return n;
}

void TerrainNode::invalidateAll() {
    std::lock_guard<std::mutex> lock(mutex_);
    invalidateLocked({++generation_, {}, true});
}

void TerrainNode::invalidateLocked(const Invalidation& inv) {
    invalidations_.push_back(inv);
    if (invalidations_.size() > 1024) invalidations_.erase(invalidations_.begin());
    failed_.clear();
    std::vector<TileKey> gone;
    store_->forEach([&](const TileKey& key, ResidentTile& tile) {
        if (!inv.everything && !touches(key, inv.region)) return;
        // Tiles in view keep being drawn until their rebuild is swapped in; the rest just go.
        const bool in_view = cull_frame_ != ~0u && tile.last_used_frame + 1 >= cull_frame_;
        if (in_view) {
            tile.dirty = true;
            ++stats_.tiles_invalidated;
        } else {
            gone.push_back(key);
        }
    });
    for (const TileKey& key : gone) release(store_->remove(key), cull_frame_);
    // Start the rebuilds of the edited tiles on screen now rather than after the next cull has
    // wanted them and the UPDATE after it has planned them: that waited one to two frames (40-80 ms
    // while the editor drags on llvmpipe). The next UPDATE re-plans as usual.
    if (wantDrawnDirtyTiles()) planBuilds();
}

void TerrainNode::setHeightSource(HeightSource source) {
    std::lock_guard<std::mutex> lock(mutex_);
    source_ = std::move(source);
}

Status TerrainNode::preload(const PixelWindow& region, int level) {
    TERRASYNTH_REQUIRE(level >= 0, "preload level must be >= 0");
    const std::vector<TileKey> keys = tilesCovering(region, level);

    HeightSource source;
    TypeSource types;
    uint64_t generation;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        source = source_;
        types = type_source_;
        generation = generation_;
    }
    std::vector<TileBuild> builds = loader_->buildNow(keys, source, types);

    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& b : builds)
        if (!b.status) return b.status.withContext("preload");
    removeChildren(0, getNumChildren());
    for (auto& b : builds) {
        b.generation = generation;
        osg::ref_ptr<osg::Node> node = b.node;
        attach(std::move(b));
        addChild(node.get());
    }
    return Status::ok();
}

Status TerrainNode::runOnEveryWorker(const std::function<Status()>& fn) const {
    std::mutex failure_mutex;
    Status first_failure = Status::ok();
    loader_->runOnEveryThread([&] {
        Status s = fn();
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!s && first_failure) first_failure = std::move(s);
    });
    return first_failure;
}

TerrainStats TerrainNode::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    TerrainStats s = stats_;
    s.resident_tiles = store_->size();
    s.resident_bytes = store_->bytes();
    s.pending_builds = loader_->busyCount();
    s.waiting_merge = loader_->finishedCount();
    s.wanted_tiles = wanted_.size();
    s.drawn_tiles = drawn_.size();
    s.prefetch_requests = 0;
    for (const auto& [key, frame] : prefetch_) s.prefetch_requests += store_->find(key) == nullptr;
    const TileLoader::Totals totals = loader_->totals();
    s.tiles_built = totals.built;
    const double n = static_cast<double>(std::max<uint64_t>(1, totals.built));
    s.mean_build_ms = totals.build_ms / n;
    s.mean_heights_ms = totals.heights_ms / n;
    return s;
}

std::vector<double> TerrainNode::mergeTimesMs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return merge_times_;
}

void TerrainNode::resetMergeStats() {
    std::lock_guard<std::mutex> lock(mutex_);
    merge_times_.clear();
    stats_.max_merge_ms = 0.0;
}

bool TerrainNode::settled() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (loader_->busyCount() != 0 || loader_->finishedCount() != 0) return false;
    for (const auto& [key, priority] : wanted_) {
        if (failed_.count(key)) continue;
        const ResidentTile* tile = store_->find(key);
        if (!tile || tile->dirty) return false;
    }
    return true;
}

std::vector<TileKey> TerrainNode::drawnTiles() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return drawn_keys_;
}

osg::ref_ptr<osg::Node> TerrainNode::tileNode(const TileKey& key) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const ResidentTile* tile = store_->find(key);
    return tile ? tile->node : nullptr;
}

}  // namespace terrasynth::plugin
