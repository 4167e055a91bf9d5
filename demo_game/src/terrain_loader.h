// Opens the project's Terrain on a background thread (loading, or building and caching, the exemplar
// database) so the window can show progress instead of a frozen screen. Private to the game.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "terrasynth/terrain.h"

namespace terrasynth::game {

class TerrainLoader {
public:
    // Starts at once. options.database.progress is replaced by the loader's own. `after_open` (may be
    // empty) runs on the loader's thread once the terrain is open, before done() (e.g. a first
    // synthesis, which also compiles the kernels).
    TerrainLoader(Project project, TerrainOptions options, std::function<void(Terrain&)> after_open);
    ~TerrainLoader();  // joins (a database build in progress finishes first)
    TerrainLoader(const TerrainLoader&) = delete;
    TerrainLoader& operator=(const TerrainLoader&) = delete;

    bool done() const { return done_.load(); }
    // What the database build is doing and how far (0..1); "loading" while it only loads.
    std::string stage() const;
    double progress() const;
    // The result, once done().
    Result<std::shared_ptr<Terrain>> result() const;

private:
    mutable std::mutex mutex_;
    std::string stage_ = "loading the exemplar database";
    double progress_ = 0.0;
    std::atomic<bool> done_{false};
    Result<std::shared_ptr<Terrain>> result_ = Status::error("still loading");
    std::thread thread_;
};

}  // namespace terrasynth::game
