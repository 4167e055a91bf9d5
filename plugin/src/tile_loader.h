// tile_loader.h: builds tiles off the draw thread (osgEarth REX's loader): a worker pool whose queue
// is re-planned every frame, and the finished builds waiting for an UPDATE to merge them.
//
// A key is *busy* from the plan that queues its build until the UPDATE that merges or drops that
// build calls done(): re-planning drops the queued builds nobody wants any more, never starts a
// second build of a busy key, and lets started builds finish. Thread-safe; the workers take only
// the loader's lock, so a build never waits for a cull or an UPDATE.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "terrasynth_plugin/height_source.h"
#include "terrasynth_plugin/tile_key.h"
#include "tile_builder.h"
#include "worker_pool.h"

namespace terrasynth::plugin {

class TileLoader {
public:
    struct Request {
        TileKey key;
        double priority = 0.0;  // lower builds first
        // The resident parent's data for the geomorph targets; null = read them from the source.
        std::shared_ptr<const TileData> parent;
    };
    struct Totals {
        uint64_t built = 0;  // builds finished by the workers
        double build_ms = 0.0, heights_ms = 0.0;  // their summed worker time, and the reading part of it
    };

    // threads >= 1 workers, started at once.
    TileLoader(const TileBuildSettings& settings, int threads);
    // Drops the queued builds and waits for the running ones.
    ~TileLoader();
    TileLoader(const TileLoader&) = delete;
    TileLoader& operator=(const TileLoader&) = delete;

    const TileBuildSettings& settings() const { return settings_; }
    int threadCount() const { return pool_->threadCount(); }

    // Replaces the queue: drops every queued build, then queues the requests whose key is not busy,
    // best priority first, reading `source` (and `types`) for edit `generation`.
    void plan(std::vector<Request> requests, const HeightSource& source, const TypeSource& types, uint64_t generation);
    // Takes the finished builds, oldest first. Their keys stay busy until done().
    std::vector<TileBuild> takeFinished();
    // Returns finished builds an UPDATE had no time for; they are taken first next time, in this order.
    void putBack(std::vector<TileBuild> builds);
    // The build of `key` was merged or dropped: the key is no longer busy.
    void done(const TileKey& key);
    size_t busyCount() const;      // queued, running, or finished and not yet done
    size_t finishedCount() const;  // finished and not yet taken
    Totals totals() const;

    // Builds `keys` at once on the workers, beside the queue (preload), and returns when all are
    // built. Builds are in the order of `keys`, without geomorph parents.
    std::vector<TileBuild> buildNow(const std::vector<TileKey>& keys, const HeightSource& source,
                                    const TypeSource& types) const;
    // WorkerPool::runOnEveryThread.
    void runOnEveryThread(const std::function<void()>& fn) const { pool_->runOnEveryThread(fn); }

private:
    struct Building {
        uint64_t ticket;  // which submission owns the key (re-planning may re-submit it)
        bool started;
    };
    // The worker side of one build.
    void run(const TileKey& key, uint64_t ticket, uint64_t generation, const HeightSource& source,
             const TypeSource& types, const TileData* parent);

    const TileBuildSettings settings_;
    mutable std::mutex mutex_;  // everything below but the pool
    std::unordered_map<TileKey, Building, TileKeyHash> building_;  // the busy keys
    uint64_t next_ticket_ = 0;
    std::vector<TileBuild> finished_;
    Totals totals_;
    std::unique_ptr<WorkerPool> pool_;  // last: destroyed (joined) first
};

}  // namespace terrasynth::plugin
