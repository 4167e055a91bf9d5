// terrasynth_game/exact_ground.h: exact ground heights for collision, without a frame ever waiting.
//
// "Exact" means the synthesized terrain's own level-0 samples (a HeightSource such as
// Terrain::heights, bit-identical for any window) interpolated on the mesh's triangles
// (heightOnGridCell in terrasynth/mesh.h): the surface a level-0 tile draws. exactGroundSample is
// the one place that asks the source for it; when the runtime gains heightAt / heightsAt
// (EditSession, Terrain) only that function and GroundCache::fetch change.
//
// GroundCache keeps blocks of samples (65 x 65, any level) around what the game says it needs,
// fetched by one worker thread at a lower CPU priority, most wanted first. Queries read only cached
// blocks: a missing block is an answer (nullopt), never a wait.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "terrasynth/grid.h"

namespace terrasynth::game {

struct GroundSample {
    double height_m = 0.0;
    double normal[3] = {0.0, 0.0, 1.0};  // unit, x east, y north, z up: of the triangle under the point
};

// The ground at world (wx, wy) from the four level-0 samples around it (nw, ne, sw, se, with the
// point at (fu, fw) from the north-west sample, spacing metres apart).
GroundSample groundOnCell(double nw, double ne, double sw, double se, double fu, double fw, double spacing);

// One exact query straight from the source (a 2x2 window at level 0: one small synthesis, ~ms).
// For tests and one-off use; the game reads GroundCache.
Result<GroundSample> exactGroundSample(const HeightSource& source, double meters_per_pixel, double wx, double wy);

struct BlockKey {
    int level = 0;
    int64_t bx = 0, by = 0;  // block indices: samples [bx * kBlock, bx * kBlock + kBlock] of the level
    bool operator==(const BlockKey& o) const { return level == o.level && bx == o.bx && by == o.by; }
};
struct BlockKeyHash {
    size_t operator()(const BlockKey& k) const {
        return static_cast<size_t>(k.bx * 0x9E3779B97F4A7C15ull ^ (k.by + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full ^
                                   static_cast<uint64_t>(k.level) << 56);
    }
};

class GroundCache {
public:
    static constexpr int kBlock = 64;  // quads per block side; a block holds kBlock + 1 samples per side

    // meters_per_pixel: level-0 spacing of `source`. The worker starts at once and idles.
    GroundCache(HeightSource source, double meters_per_pixel, size_t max_blocks = 1024);
    // Stops the worker (a fetch in progress finishes) and joins it.
    ~GroundCache();
    GroundCache(const GroundCache&) = delete;
    GroundCache& operator=(const GroundCache&) = delete;

    // The blocks of `level` touching the disc of radius_m around world (wx, wy), nearest first.
    std::vector<BlockKey> blocksAround(int level, double wx, double wy, double radius_m) const;
    // Replaces the list of blocks the game needs, most urgent first. Thread-safe.
    void want(std::vector<BlockKey> keys);
    // True when every wanted block is cached (or failed).
    bool idle() const;

    // Level-0 ground from cached blocks; nullopt when the block holding the point's cell is not cached.
    std::optional<GroundSample> sample(double wx, double wy) const;
    // A cached block (kBlock + 1 samples per side, at its level's spacing), or null.
    std::shared_ptr<const Heightfield> block(const BlockKey& key) const;
    // The block key of level-`level` sample (px, py).
    static BlockKey blockOf(int level, int64_t px, int64_t py);
    double metersPerPixel() const { return meters_per_pixel_; }
    // The most blocks kept (least recently wanted dropped first).
    size_t maxBlocks() const { return max_blocks_; }

    struct Stats {
        size_t cached = 0, fetched = 0, failed = 0;
        double mean_fetch_ms = 0.0, max_fetch_ms = 0.0;
        std::string last_error;
    };
    Stats stats() const;

private:
    void workerLoop();
    Result<Heightfield> fetch(const BlockKey& key) const;

    const HeightSource source_;
    const double meters_per_pixel_;
    const size_t max_blocks_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::vector<BlockKey> wanted_;
    struct Entry {
        std::shared_ptr<const Heightfield> field;
        uint64_t last_wanted = 0;
    };
    std::unordered_map<BlockKey, Entry, BlockKeyHash> blocks_;
    std::unordered_map<BlockKey, std::string, BlockKeyHash> failed_;
    uint64_t want_tick_ = 0;
    bool stopping_ = false;
    Stats stats_;
    double fetch_ms_sum_ = 0.0;
    std::thread worker_;  // last: started after everything it reads
};

}  // namespace terrasynth::game
