#include "tile_loader.h"

#include <algorithm>
#include <atomic>
#include <iterator>
#include <utility>

namespace terrasynth::plugin {

TileLoader::TileLoader(const TileBuildSettings& settings, int threads)
    : settings_(settings), pool_(std::make_unique<WorkerPool>(threads)) {}

TileLoader::~TileLoader() { pool_.reset(); }

void TileLoader::plan(std::vector<Request> requests, const HeightSource& source, const TypeSource& types,
                      uint64_t generation) {
    std::lock_guard<std::mutex> lock(mutex_);
    // Queued (not started) builds are about to be replaced by this plan.
    for (auto it = building_.begin(); it != building_.end();)
        it = it->second.started ? std::next(it) : building_.erase(it);
    requests.erase(std::remove_if(requests.begin(), requests.end(),
                                  [this](const Request& r) { return building_.count(r.key) != 0; }),
                   requests.end());
    std::sort(requests.begin(), requests.end(), [](const Request& a, const Request& b) { return a.priority < b.priority; });
    std::vector<WorkerPool::Task> tasks;
    tasks.reserve(requests.size());
    for (Request& r : requests) {
        const uint64_t ticket = ++next_ticket_;
        building_[r.key] = {ticket, false};
        tasks.push_back({r.priority, [this, key = r.key, ticket, generation, source, types, parent = std::move(r.parent)] {
                             run(key, ticket, generation, source, types, parent.get());
                         }});
    }
    pool_->replaceQueue(std::move(tasks));
}

void TileLoader::run(const TileKey& key, uint64_t ticket, uint64_t generation, const HeightSource& source,
                     const TypeSource& types, const TileData* parent) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = building_.find(key);
        // Popped just before a re-plan dropped it (no entry), or a newer submission owns the key:
        // nothing to do. The re-plan queued again whatever is still wanted; claiming the key here
        // built a tile twice when the newer build had already been merged (its done() erased the
        // entry) by the time this worker got the lock.
        if (it == building_.end() || it->second.ticket != ticket || it->second.started) return;
        it->second.started = true;
    }
    TileBuild build = buildTile(source, key, settings_, parent, &types);
    build.generation = generation;
    std::lock_guard<std::mutex> lock(mutex_);
    ++totals_.built;
    totals_.build_ms += build.heights_ms + build.mesh_ms + build.osg_ms;
    totals_.heights_ms += build.heights_ms;
    finished_.push_back(std::move(build));
}

std::vector<TileBuild> TileLoader::takeFinished() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(finished_, {});
}

void TileLoader::putBack(std::vector<TileBuild> builds) {
    if (builds.empty()) return;
    std::lock_guard<std::mutex> lock(mutex_);
    builds.insert(builds.end(), std::make_move_iterator(finished_.begin()), std::make_move_iterator(finished_.end()));
    finished_ = std::move(builds);
}

void TileLoader::done(const TileKey& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    building_.erase(key);
}

size_t TileLoader::busyCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return building_.size();
}

size_t TileLoader::finishedCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return finished_.size();
}

TileLoader::Totals TileLoader::totals() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return totals_;
}

std::vector<TileBuild> TileLoader::buildNow(const std::vector<TileKey>& keys, const HeightSource& source,
                                            const TypeSource& types) const {
    // On the workers themselves, so the synthesizers the preload makes are the ones they build
    // tiles with afterwards (short-lived threads each made one and left it behind).
    std::vector<TileBuild> builds(keys.size());
    std::atomic<size_t> next{0};
    pool_->runOnEveryThread([&] {
        for (size_t i = next++; i < keys.size(); i = next++) builds[i] = buildTile(source, keys[i], settings_, nullptr, &types);
    });
    return builds;
}

}  // namespace terrasynth::plugin
