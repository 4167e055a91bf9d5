// UPDATE: attach finished tiles under a per-frame budget, re-plan the loader's queue from what the
// last cull wanted, and evict what the store's unloader policy picks beyond the memory budget.
#include <algorithm>
#include <chrono>
#include <iterator>
#include <limits>

#include <osg/Notify>

#include "terrasynth_plugin/terrain_node.h"
#include "tile_loader.h"
#include "tile_store.h"

namespace terrasynth::plugin {
namespace {
constexpr size_t kMergeHistory = 4096;
constexpr unsigned kReleaseDelayFrames = 3;  // a draw thread may still hold last frame's tiles
constexpr double kPrefetchPriority = 1e6;   // after every tile the cull wants (those are < 1e3)
}  // namespace

void TerrainNode::update(unsigned frame) {
    std::lock_guard<std::mutex> lock(mutex_);
    mergeCompleted(frame);
    planBuilds();
    evict(frame);
    syncChildren();
    released_.erase(std::remove_if(released_.begin(), released_.end(),
                                   [frame](const auto& r) { return r.first + kReleaseDelayFrames < frame ||
                                                                   r.first == ~0u; }),
                    released_.end());
}

void TerrainNode::mergeCompleted(unsigned frame) {
    std::vector<TileBuild> completed = loader_->takeFinished();
    if (completed.empty()) {
        stats_.last_merge_count = 0;
        stats_.last_merge_ms = 0.0;
        return;
    }
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    // Most wanted first; tiles nobody wants any more last.
    auto priority = [this](const TileBuild& b) {
        auto it = wanted_.find(b.key);
        return it == wanted_.end() ? std::numeric_limits<double>::max() : it->second;
    };
    std::stable_sort(completed.begin(), completed.end(),
                     [&](const TileBuild& a, const TileBuild& b) { return priority(a) < priority(b); });
    int merged = 0;
    double elapsed = 0.0;
    size_t taken = 0;
    while (taken < completed.size() && merged < options_.max_merges_per_frame) {
        // Stop before an attach that would likely overrun the budget (always do one: progress).
        if (merged > 0 && elapsed + merge_cost_ema_ms_ > options_.merge_budget_ms) break;
        const auto ta = clock::now();
        TileBuild build = std::move(completed[taken++]);
        const TileKey key = build.key;
        attach(std::move(build));
        if (ResidentTile* tile = store_->find(key)) tile->last_used_frame = frame;
        const double cost = std::chrono::duration<double, std::milli>(clock::now() - ta).count();
        merge_cost_ema_ms_ = 0.8 * merge_cost_ema_ms_ + 0.2 * cost;
        ++merged;
        elapsed = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
    }
    // What had no time this frame waits for the next, ahead of builds finished meanwhile.
    loader_->putBack({std::make_move_iterator(completed.begin() + static_cast<std::ptrdiff_t>(taken)),
                      std::make_move_iterator(completed.end())});
    elapsed = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
    stats_.last_merge_count = merged;
    stats_.last_merge_ms = elapsed;
    stats_.max_merge_ms = std::max(stats_.max_merge_ms, elapsed);
    if (merge_times_.size() >= kMergeHistory) merge_times_.erase(merge_times_.begin());
    merge_times_.push_back(elapsed);
}

bool TerrainNode::staleLocked(const TileKey& key, uint64_t generation) const {
    if (!invalidations_.empty() && generation + 1 < invalidations_.front().generation) return true;
    for (const auto& inv : invalidations_)
        if (inv.generation > generation && (inv.everything || touches(key, inv.region))) return true;
    return false;
}

void TerrainNode::attach(TileBuild&& build) {
    loader_->done(build.key);
    if (!build.status) {
        ++stats_.build_failures;
        stats_.last_error = build.status.message();
        failed_.insert(build.key);
        OSG_WARN << "terrasynth: " << build.status.message() << std::endl;
        return;
    }
    ResidentTile* tile = store_->find(build.key);
    if (staleLocked(build.key, build.generation)) {
        // Read before an edit touching it. A tile still on screen with older heights takes it anyway
        // and stays marked for the newest: while an editor drags, every edit invalidates the same
        // tiles again, and waiting for a build no later edit overtakes would show nothing until the
        // drag stops. Otherwise the (still dirty or missing) tile will be wanted again.
        if (!tile || !tile->dirty || build.generation <= tile->generation) {
            ++stats_.stale_builds_dropped;
            return;
        }
        swapIn(*tile, std::move(build));
        return;
    }
    if (tile) {
        swapIn(*tile, std::move(build));
        tile->dirty = false;
        return;
    }
    store_->add(std::move(build), cull_frame_ == ~0u ? 0 : cull_frame_);
    ++stats_.tiles_merged;
}

void TerrainNode::swapIn(ResidentTile& tile, TileBuild&& build) {
    tile.generation = build.generation;
    if (sameSamples(*tile.data, *build.data)) {
        ++stats_.rebuilds_unchanged;  // the edit did not reach this tile's samples
        return;
    }
    replaceChild(tile.node.get(), build.node.get());
    released_.emplace_back(cull_frame_, store_->replace(tile, std::move(build)));
    ++stats_.tiles_swapped;
    ++stats_.tiles_merged;
}

void TerrainNode::planBuilds() {
    // Geomorph targets come from the resident parent (always there when a child is wanted) rather
    // than from a second synthesis call.
    auto parentData = [this](const TileKey& key) -> std::shared_ptr<const TileData> {
        if (!options_.geomorph || key.level >= options_.max_level) return nullptr;
        const ResidentTile* parent = store_->find(key.parent());
        return parent && !parent->dirty ? parent->data : nullptr;
    };
    std::vector<TileLoader::Request> requests;
    requests.reserve(wanted_.size());
    for (const auto& [key, priority] : wanted_) {
        const ResidentTile* tile = store_->find(key);
        if (tile && !tile->dirty) continue;
        requests.push_back({key, priority, parentData(key)});
    }
    // Prefetch requests come after everything the cull wants, coarsest level first (a tile is only
    // drawn once its parent is); requests not repeated for two frames lapse.
    for (auto it = prefetch_.begin(); it != prefetch_.end();) {
        const TileKey key = it->first;
        const bool lapsed = cull_frame_ != ~0u && it->second + 2 < cull_frame_;
        const ResidentTile* tile = store_->find(key);
        if (lapsed || (tile && !tile->dirty)) {
            it = prefetch_.erase(it);
            continue;
        }
        ++it;
        if (wanted_.count(key) || failed_.count(key)) continue;
        requests.push_back({key, kPrefetchPriority - key.level, parentData(key)});
    }
    // The loader leaves out what it is already building.
    loader_->plan(std::move(requests), source_, type_source_, generation_);
}

void TerrainNode::syncChildren() {
    if (cull_frame_ == ~0u) return;  // keep the preload until a camera has chosen
    bool same = getNumChildren() == drawn_.size();
    for (size_t i = 0; same && i < drawn_.size(); ++i) same = getChild(static_cast<unsigned>(i)) == drawn_[i].get();
    if (same) return;
    removeChildren(0, getNumChildren());
    for (auto& node : drawn_) addChild(node.get());
}

void TerrainNode::release(osg::ref_ptr<osg::Node> node, unsigned frame) {
    removeChild(node.get());
    released_.emplace_back(frame, std::move(node));
}

void TerrainNode::evict(unsigned frame) {
    if (cull_frame_ == ~0u) return;
    const size_t budget = static_cast<size_t>(options_.cache_mb * 1024.0 * 1024.0);
    for (const TileKey& key : tilesToEvict(*store_, budget, cull_frame_)) {
        release(store_->remove(key), frame);
        ++stats_.tiles_evicted;
    }
}

}  // namespace terrasynth::plugin
