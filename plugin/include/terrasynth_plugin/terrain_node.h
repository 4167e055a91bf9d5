// terrasynth_plugin/terrain_node.h: the unbounded quadtree terrain as one OSG node.
//
// Data model vs render model (osgEarth REX style). Every resident tile keeps the plain data it was
// built from (its key and its height samples, apron included, and type ids) beside the OSG geometry
// drawn from it; surface heights, geomorph targets and edit comparisons read the data, never the
// geometry. The node does the cull and the update itself and leaves building and residency to
// collaborators private to the plugin (a loader, a store):
//  - CULL: picks the tiles to draw by screen-space error from the camera, starting from the
//    root tiles (level max_level) within view_radius of the eye, so the world follows the camera
//    without bounds. A tile is refined only once all four children are resident; until then it is
//    drawn itself (no holes) and its missing children are wanted. Skirts hide the LOD steps (no cracks).
//  - The loader: worker threads build each wanted tile (heights -> data -> mesh -> detached OSG
//    node), nearest first; the queue is re-planned every frame so tiles left behind are dropped.
//  - UPDATE: finished tiles are attached (or swapped for a rebuilt tile) under a per-frame cap
//    on the count and on the measured main-thread time.
//  - The store: the resident tiles and their memory; its unloader policy then picks the least
//    recently drawn tiles to evict until the resident memory fits the cache budget.
// Editing: invalidate() marks the tiles whose heights may change; they are rebuilt in the background
// (those drawn first, the coarser ones above them after) and swapped whole (new geometry, never
// DYNAMIC edits) only when their samples actually differ.
//
// Threading: OSG calls traverse() from the update and cull threads (never both at once for one
// frame in osgViewer, but a mutex guards the shared state anyway); the other public methods are
// thread-safe. The children are the tiles drawn in the last frame (before any frame: the last
// preload), one consistent set of LODs for intersection visitors and writers; the node keeps the
// class name of osg::Group so osgconv stores them as a plain group of transforms and geometries.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <osg/Group>
#include <osg/NodeVisitor>

#include "terrasynth_plugin/height_source.h"
#include "terrasynth_plugin/terrain_look.h"
#include "terrasynth_plugin/tile_key.h"

namespace osgUtil {
class CullVisitor;
}

namespace terrasynth::plugin {

struct ResidentTile;
struct TileBuild;
class TileLoader;
class TileStore;

struct TerrainNodeOptions {
    int tile_size = 256;      // quads per tile side (tile_size + 1 samples); 8..2048
    int max_level = 5;        // level of the root tiles (coarsest); >= min_level
    int min_level = 0;        // finest level drawn; >= 0
    int mesh_step = 1;        // grid step in samples; divides tile_size
    // A tile is refined while one sample spacing of it projects to more than this many pixels.
    float pixel_error = 8.0f;
    // Root tiles whose footprint comes within this distance (metres, horizontal) of the eye are drawn;
    // 0 = 3 root tiles. Root tiles within 1.5x of it are loaded ahead of the camera.
    double view_radius_m = 0.0;
    int threads = 0;          // worker threads; 0 = hardware threads
    // Resident tile memory budget (MiB): client-side vertex and index bytes plus the height samples
    // each tile keeps. Tiles drawn in the last frame are never evicted, so a view needing more
    // overshoots rather than showing holes.
    double cache_mb = 768.0;
    int max_merges_per_frame = 16;  // tiles attached per UPDATE at most
    double merge_budget_ms = 2.0;   // main-thread time per UPDATE for attaching tiles
    float skirt_extra_spacings = 2.0f;
    bool optimize_order = false;
    // Blend each tile towards its parent's surface before the parent takes over (no popping).
    // Needs an even tile_size / mesh_step; costs a quarter more height samples per tile.
    bool geomorph = true;
};

// Checks ranges (numbers finite); the message names the option.
Status validateOptions(const TerrainNodeOptions& options);
// max_level clamped to the coarsest level of a database of `database_levels` levels (levelCount()),
// never below min_level: the root tiles' level when maxLevel was not given.
int clampedMaxLevel(const TerrainNodeOptions& options, int database_levels);

struct TerrainStats {
    size_t resident_tiles = 0;
    size_t resident_bytes = 0;
    size_t pending_builds = 0;    // queued or running on workers
    size_t waiting_merge = 0;     // built, waiting for an UPDATE
    size_t drawn_tiles = 0;       // in the last cull
    size_t drawn_triangles = 0;   // of the tiles drawn in the last cull (skirts included)
    size_t prefetch_requests = 0; // tiles asked for by prefetch() and not yet resident
    size_t wanted_tiles = 0;      // in the last cull
    float drawn_min_height = 0.0f, drawn_max_height = 0.0f;  // over the tiles drawn in the last cull
    uint64_t tiles_built = 0, tiles_merged = 0, tiles_swapped = 0, rebuilds_unchanged = 0;
    uint64_t tiles_evicted = 0, build_failures = 0, stale_builds_dropped = 0;
    uint64_t tiles_invalidated = 0;  // resident tiles in view marked for a rebuild by invalidate*()
    int last_merge_count = 0;
    double last_merge_ms = 0.0;   // main-thread time of the last UPDATE's merge step
    double max_merge_ms = 0.0;    // largest since construction (or resetMergeStats)
    double mean_build_ms = 0.0;   // worker time per tile (heights + mesh + node)
    double mean_heights_ms = 0.0;
    std::string last_error;       // last failed build, "" if none
};

class TerrainNode : public osg::Group {
public:
    // meters_per_pixel: level-0 spacing of `source`. Options must pass validateOptions.
    TerrainNode(HeightSource source, double meters_per_pixel, const TerrainNodeOptions& options);

    void traverse(osg::NodeVisitor& nv) override;
    // What viewers derive their home position from (osgGA manipulators put the eye south of the
    // sphere's centre, at its height, looking north horizontally, at radius / sin(half fov)).
    // With a home extent (setHomeExtent) the sphere is chosen so that this eye sees the whole extent
    // obliquely from above: the eye 1.3 extents south of its near edge, high enough to look down on
    // its near edge at 11 degrees (stock osgviewer's half field of view is 14.6). Without one, the children's
    // bound stretched upwards by two radii (so the eye is above the surrounding relief).
    osg::BoundingSphere computeBound() const override;
    // The level-0 region the home view shows (e.g. the project extent). Its height range is taken
    // from the resident tiles over it, so call it after preload().
    void setHomeExtent(const PixelWindow& level0_extent);

    // The look (terrain_look.h): sun, tints, fog, type colours. Thread-safe; takes effect next draw.
    void setLook(const TerrainLook& look);
    TerrainLook look() const;
    // Where type colours come from (e.g. a Terrain's synthesized source map); tiles built afterwards
    // carry type ids (call invalidateAll() to rebuild resident tiles). Empty = none.
    void setTypeSource(TypeSource types);

    // Height of the terrain surface at world (x, y) as drawn without geomorphing: interpolated on the
    // triangles of the finest resident tile containing the point (the mesh's own split: each cell's
    // north-east to south-west diagonal). Within that tile's geometric error of the source's heights
    // (exact at the samples of level-0 tiles). nullopt when no resident tile contains the point.
    // `tile_level` (optional) receives the level of the tile that answered. Thread-safe; takes the
    // node's lock only to find the tile.
    std::optional<float> heightAt(double world_x, double world_y, int* tile_level = nullptr) const;
    // Min and max height of the finest resident tiles over a level-0 region; nullopt if none.
    std::optional<std::pair<float, float>> heightRange(const PixelWindow& level0_region) const;

    // Asks for the tiles of `level` covering the level-0 pixel rectangle `region` to be built ahead
    // of need (e.g. along a predicted flight path), after everything the cull wants. A request holds
    // for the next two UPDATEs: repeat it every frame while it is still wanted. Thread-safe.
    void prefetch(const PixelWindow& level0_region, int level);
    // Distance (metres, eye to tile box) within which the last cull drew tiles of `level` rather than
    // their parent: what prefetching around a future eye position needs. The view radius for the
    // root level; 0 before the first cull.
    double refinementDistance(int level) const;

    // Builds the tiles of `level` that cover the level-0 pixel rectangle `region` on the workers,
    // waits, makes them resident and the node's children (for osgconv, bounds and first frames;
    // preload the root level too so the first frame has something to draw). Errors: a failed tile.
    Status preload(const PixelWindow& region, int level);
    // Runs `fn` once on each worker thread and returns when all have: for what belongs to a thread
    // and should exist before the frame loop starts (each worker's synthesizer: Terrain's
    // prepareThisThread). Returns the first failure any worker's `fn` returned, else ok. `fn` must
    // not call back into the node. Thread-safe.
    Status runOnEveryWorker(const std::function<Status()>& fn) const;

    // Marks every tile whose samples (apron included) may change when the level-0 heights inside
    // `region` change, widened by `margin_px` level-0 pixels for filters that spread an edit.
    // Marked tiles still drawn are rebuilt and swapped when their heights differ; others are dropped.
    // Returns the invalidation's generation (increasing), for tilesAwaitingRebuild().
    uint64_t invalidate(const PixelWindow& region, int64_t margin_px = 0);
    void invalidateAll();
    // Tiles drawn by the last cull whose heights predate invalidation `generation`: marked by it (or
    // an earlier one) and not yet rebuilt. 0 = everything that invalidation changed on screen has
    // been swapped in (or found unchanged) by an UPDATE, e.g. for an editor's edit-to-screen latency.
    // While edits keep coming, a rebuild read between two of them is swapped in (it is newer than
    // what is drawn) and the tile stays marked for the newest.
    size_t tilesAwaitingRebuild(uint64_t generation) const;
    // Replaces the height source (e.g. after an edit); call invalidate*() for the changed area.
    void setHeightSource(HeightSource source);

    TerrainStats stats() const;
    // Per-UPDATE merge times (ms) of the UPDATEs that attached at least one tile, oldest first
    // (the last 4096).
    std::vector<double> mergeTimesMs() const;
    void resetMergeStats();
    // True when nothing is wanted, building, or waiting to merge (the view has converged).
    bool settled() const;
    const TileLayout& layout() const { return layout_; }
    const TerrainNodeOptions& options() const { return options_; }
    // Tiles drawn by the last cull (for tests).
    std::vector<TileKey> drawnTiles() const;
    // The resident node of a tile, or null (for tests: a swap gives a new pointer).
    osg::ref_ptr<osg::Node> tileNode(const TileKey& key) const;

protected:
    ~TerrainNode() override;

private:
    struct Invalidation {
        uint64_t generation;
        PixelWindow region;  // level 0, margin included
        bool everything;
    };

    // CULL
    void cull(osgUtil::CullVisitor& cv);
    void cullFrom(osgUtil::CullVisitor& cv, unsigned frame);  // roots around the eye, then selectTile
    void selectTile(osgUtil::CullVisitor& cv, const TileKey& key, ResidentTile& tile);
    void want(const TileKey& key, double priority);
    // Wants the tiles the last cull drew that an edit has just marked dirty, as that cull would
    // have; true when there were any.
    bool wantDrawnDirtyTiles();
    double screenPixelsPerMeter(osgUtil::CullVisitor& cv, double distance) const;
    // UPDATE
    void update(unsigned frame);
    void mergeCompleted(unsigned frame);
    void attach(TileBuild&& build);
    void swapIn(ResidentTile& tile, TileBuild&& build);  // a rebuild of a resident tile (unless unchanged)
    void planBuilds();
    void evict(unsigned frame);
    // Takes a tile's node out of the children, kept alive until no draw thread can hold it.
    void release(osg::ref_ptr<osg::Node> node, unsigned frame);
    // Children = the tiles the last cull drew (what writers and intersection visitors see).
    void syncChildren();
    std::vector<TileKey> tilesCovering(const PixelWindow& level0_region, int level) const;
    bool staleLocked(const TileKey& key, uint64_t generation) const;
    void invalidateLocked(const Invalidation& inv);
    bool touches(const TileKey& key, const PixelWindow& level0_region) const;

    TerrainNodeOptions options_;
    TileLayout layout_;

    mutable std::mutex mutex_;  // everything below but the loader, which has its own
    HeightSource source_;
    TypeSource type_source_;
    std::unique_ptr<TileStore> store_;                             // the resident tiles
    std::unordered_map<TileKey, unsigned, TileKeyHash> prefetch_;  // key -> frame of the request
    std::unordered_map<TileKey, double, TileKeyHash> wanted_;      // by the last cull
    std::unordered_set<TileKey, TileKeyHash> failed_;              // not retried until an edit
    std::vector<Invalidation> invalidations_;
    std::vector<std::pair<unsigned, osg::ref_ptr<osg::Node>>> released_;  // kept alive a few frames
    std::vector<osg::ref_ptr<osg::Node>> drawn_;
    std::vector<TileKey> drawn_keys_;
    unsigned cull_frame_ = ~0u;
    unsigned frame_counter_ = 0;
    uint64_t generation_ = 0;
    double merge_cost_ema_ms_ = 0.2;
    TerrainStats stats_;
    std::vector<double> merge_times_;
    // Per-cull state carrying ts_lod_k, kept alive while a draw thread may still use it.
    std::vector<std::pair<unsigned, osg::ref_ptr<osg::StateSet>>> lod_states_;
    double pixels_per_meter_at_1m_ = 0.0;  // of the last cull's camera (LOD scale included)
    TerrainLook look_;
    mutable std::mutex home_mutex_;   // home_bound_ (computeBound must not wait for mutex_)
    osg::BoundingSphere home_bound_;  // valid once setHomeExtent was called

    std::unique_ptr<TileLoader> loader_;  // last: its workers are joined first
};

}  // namespace terrasynth::plugin
