// UPDATE: attach finished tiles under a per-frame budget, re-plan the workers' queue from what the
// last cull wanted, and evict least-recently drawn tiles beyond the memory budget. Plus the worker
// side of a build (runBuild), which only touches shared state under the mutex.
#include <algorithm>
#include <chrono>
#include <limits>

#include <osg/Notify>

#include "terrasynth_plugin/terrain_node.h"

namespace terrasynth::plugin {
namespace {
constexpr size_t kMergeHistory = 4096;
constexpr unsigned kReleaseDelayFrames = 3;  // a draw thread may still hold last frame's tiles
constexpr double kPrefetchPriority = 1e6;   // after every tile the cull wants (those are < 1e3)

// Takes over a finished build's scene node and what culling and eviction need to know of it.
template <class Tile>
void adoptBuild(Tile& tile, const TileBuild& build) {
    tile.node = build.node;
    tile.box = build.box;
    tile.min_height = build.min_height;
    tile.max_height = build.max_height;
    tile.hash = build.heights_hash;
    tile.bytes = build.bytes;
    tile.triangles = build.triangles;
    tile.vertices = build.node ? tileVertices(*build.node) : nullptr;
}
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
    if (completed_.empty()) {
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
    std::stable_sort(completed_.begin(), completed_.end(),
                     [&](const TileBuild& a, const TileBuild& b) { return priority(a) < priority(b); });
    int merged = 0;
    double elapsed = 0.0;
    size_t taken = 0;
    while (taken < completed_.size() && merged < options_.max_merges_per_frame) {
        // Stop before an attach that would likely overrun the budget (always do one: progress).
        if (merged > 0 && elapsed + merge_cost_ema_ms_ > options_.merge_budget_ms) break;
        const auto ta = clock::now();
        TileBuild build = std::move(completed_[taken++]);
        const TileKey key = build.key;
        attach(std::move(build));
        auto it = tiles_.find(key);
        if (it != tiles_.end()) it->second.last_used_frame = frame;
        const double cost = std::chrono::duration<double, std::milli>(clock::now() - ta).count();
        merge_cost_ema_ms_ = 0.8 * merge_cost_ema_ms_ + 0.2 * cost;
        ++merged;
        elapsed = std::chrono::duration<double, std::milli>(clock::now() - t0).count();
    }
    completed_.erase(completed_.begin(), completed_.begin() + static_cast<std::ptrdiff_t>(taken));
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
    building_.erase(build.key);
    if (!build.status) {
        ++stats_.build_failures;
        stats_.last_error = build.status.message();
        failed_.insert(build.key);
        OSG_WARN << "terrasynth: " << build.status.message() << std::endl;
        return;
    }
    auto it = tiles_.find(build.key);
    if (staleLocked(build.key, build.generation)) {
        // Read before an edit touching it. A tile still on screen with older heights takes it anyway
        // and stays marked for the newest: while an editor drags, every edit invalidates the same
        // tiles again, and waiting for a build no later edit overtakes would show nothing until the
        // drag stops. Otherwise the (still dirty or missing) tile will be wanted again.
        if (it == tiles_.end() || !it->second.dirty || build.generation <= it->second.generation) {
            ++stats_.stale_builds_dropped;
            return;
        }
        swapIn(it->second, std::move(build));
        return;
    }
    if (it != tiles_.end()) {
        swapIn(it->second, std::move(build));
        it->second.dirty = false;
        return;
    }
    Tile tile;
    adoptBuild(tile, build);
    tile.generation = build.generation;
    tile.last_used_frame = cull_frame_ == ~0u ? 0 : cull_frame_;
    resident_bytes_ += tile.bytes;
    tiles_.emplace(build.key, std::move(tile));
    ++stats_.tiles_merged;
}

void TerrainNode::swapIn(Tile& tile, TileBuild&& build) {
    tile.generation = build.generation;
    if (tile.hash == build.heights_hash) {
        ++stats_.rebuilds_unchanged;  // the edit did not reach this tile's samples
        return;
    }
    replaceChild(tile.node.get(), build.node.get());
    released_.emplace_back(cull_frame_, tile.node);
    resident_bytes_ = resident_bytes_ - tile.bytes + build.bytes;
    adoptBuild(tile, build);
    ++stats_.tiles_swapped;
    ++stats_.tiles_merged;
}

void TerrainNode::planBuilds() {
    // Queued (not started) builds are about to be replaced by this frame's plan.
    for (auto it = building_.begin(); it != building_.end();)
        it = it->second.started ? std::next(it) : building_.erase(it);

    std::vector<std::pair<double, TileKey>> order;
    order.reserve(wanted_.size());
    for (const auto& [key, priority] : wanted_) {
        if (building_.count(key)) continue;
        auto t = tiles_.find(key);
        if (t != tiles_.end() && !t->second.dirty) continue;
        order.emplace_back(priority, key);
    }
    // Prefetch requests come after everything the cull wants, coarsest level first (a tile is only
    // drawn once its parent is); requests not repeated for two frames lapse.
    for (auto it = prefetch_.begin(); it != prefetch_.end();) {
        const TileKey key = it->first;
        const bool lapsed = cull_frame_ != ~0u && it->second + 2 < cull_frame_;
        auto t = tiles_.find(key);
        if (lapsed || (t != tiles_.end() && !t->second.dirty)) {
            it = prefetch_.erase(it);
            continue;
        }
        ++it;
        if (wanted_.count(key) || building_.count(key) || failed_.count(key)) continue;
        order.emplace_back(kPrefetchPriority - key.level, key);
    }
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<WorkerPool::Task> tasks;
    tasks.reserve(order.size());
    for (const auto& [priority, key] : order) {
        const uint64_t ticket = ++next_ticket_;
        building_[key] = {ticket, false};
        // Geomorph targets come from the resident parent (always there when a child is wanted) rather
        // than from a second synthesis call.
        osg::ref_ptr<osg::Node> parent;
        if (build_settings_.geomorph && key.level < options_.max_level) {
            auto p = tiles_.find(key.parent());
            if (p != tiles_.end() && !p->second.dirty) parent = p->second.node;
        }
        tasks.push_back({priority, [this, key, ticket, gen = generation_, source = source_, types = type_source_, parent] {
                             runBuild(key, ticket, gen, source, types, parent.get());
                         }});
    }
    pool_->replaceQueue(std::move(tasks));
}

void TerrainNode::runBuild(const TileKey& key, uint64_t ticket, uint64_t generation, const HeightSource& source,
                           const TypeSource& types, const osg::Node* parent) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = building_.find(key);
        if (it == building_.end()) {
            // Popped just before a re-plan dropped it: still worth finishing, claim the key.
            building_[key] = {ticket, true};
        } else if (it->second.ticket != ticket || it->second.started) {
            return;  // a newer submission of the same tile owns it
        } else {
            it->second.started = true;
        }
    }
    Heightfield parent_samples;
    if (parent) parent_samples = parentSamplesFromNode(*parent, key, build_settings_);
    TileBuild build = buildTile(source, key, build_settings_, parent_samples.empty() ? nullptr : &parent_samples, &types);
    build.generation = generation;
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.tiles_built;
    build_ms_sum_ += build.heights_ms + build.mesh_ms + build.osg_ms;
    heights_ms_sum_ += build.heights_ms;
    completed_.push_back(std::move(build));
}

void TerrainNode::syncChildren() {
    if (cull_frame_ == ~0u) return;  // keep the preload until a camera has chosen
    bool same = getNumChildren() == drawn_.size();
    for (size_t i = 0; same && i < drawn_.size(); ++i) same = getChild(static_cast<unsigned>(i)) == drawn_[i].get();
    if (same) return;
    removeChildren(0, getNumChildren());
    for (auto& node : drawn_) addChild(node.get());
}

void TerrainNode::evict(unsigned frame) {
    const size_t budget = static_cast<size_t>(options_.cache_mb * 1024.0 * 1024.0);
    if (resident_bytes_ <= budget || cull_frame_ == ~0u) return;
    std::vector<std::pair<unsigned, TileKey>> candidates;
    for (const auto& [key, tile] : tiles_)
        if (tile.last_used_frame < cull_frame_) candidates.emplace_back(tile.last_used_frame, key);
    // Least recently drawn first; among equals the finest (cheapest to rebuild, least coverage).
    std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first < b.first : a.second.level < b.second.level;
    });
    for (const auto& [used, key] : candidates) {
        if (resident_bytes_ <= budget) break;
        auto it = tiles_.find(key);
        resident_bytes_ -= it->second.bytes;
        released_.emplace_back(frame, it->second.node);
        removeChild(it->second.node.get());
        tiles_.erase(it);
        ++stats_.tiles_evicted;
    }
}

}  // namespace terrasynth::plugin
