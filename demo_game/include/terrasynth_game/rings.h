// terrasynth_game/rings.h: rings to fly through, along the world's ridgelines, placed from the seed.
//
// Ridges are read from level-2 heights (370 m apart with the shipped 92.6 m exemplars): a sample is
// on a ridge when it is higher than both neighbours across at least two of the four axes and stands
// above its 8 neighbours' mean; the ridge runs along the axis where the ground falls least. Among a
// block's ridge samples the seed picks (by hashing seed, block and sample, so the choice does not
// depend on which blocks were seen first) up to kRingsPerBlock, at least kMinSpacing samples apart.
// Each ring faces along its ridge, so the player flies along the crest through them, and floats
// clearance_m above the highest level-0 ground under it. Same seed and world, same rings.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <set>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "terrasynth_game/exact_ground.h"

namespace terrasynth::game {

constexpr int kRingLevel = 2;       // pyramid level ridges are read at
constexpr int kRingsPerBlock = 4;
constexpr int kMinSpacing = 8;      // samples of kRingLevel between rings of a block

struct Ring {
    uint64_t id = 0;         // unique in the world (block and sample)
    double x = 0.0, y = 0.0, z = 0.0;  // centre, world metres
    double radius_m = 70.0;
    double facing = 0.0;     // the ring's axis, radians clockwise from north (along the ridge)
};

// Ridge sites of one kRingLevel block picked for `seed` (z = the block's height there; see
// RingField for the final height).
std::vector<Ring> ridgeSites(const Heightfield& block, const BlockKey& key, double meters_per_pixel, uint32_t seed);

// True when the segment from (x0, y0, z0) to (x1, y1, z1) passes through the ring's disc.
bool passesThrough(const Ring& ring, double x0, double y0, double z0, double x1, double y1, double z1);

// The rings of the blocks around the player: sites from GroundCache's kRingLevel blocks (read on
// the caller's thread, cheap), then one worker lifts each ring above the level-0 ground under it
// (a small synthesis per ring). Thread-safe.
class RingField {
public:
    RingField(HeightSource source, double meters_per_pixel, uint32_t seed, double clearance_m = 60.0);
    ~RingField();  // joins the worker
    RingField(const RingField&) = delete;
    RingField& operator=(const RingField&) = delete;

    // The kRingLevel blocks whose rings the player may meet around (x, y): give them to GroundCache.
    std::vector<BlockKey> blocksAround(const GroundCache& ground, double x, double y) const;
    // Takes the sites of newly cached blocks among `blocks` and queues them for lifting.
    void update(const GroundCache& ground, const std::vector<BlockKey>& blocks);
    // True when every block in `blocks` has its rings finished.
    bool ready(const std::vector<BlockKey>& blocks) const;
    // Finished rings within radius_m (horizontal) of (x, y).
    std::vector<Ring> ringsNear(double x, double y, double radius_m) const;
    size_t ringCount() const;

private:
    void workerLoop();

    const HeightSource source_;
    const double meters_per_pixel_;
    const uint32_t seed_;
    const double clearance_m_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::unordered_set<BlockKey, BlockKeyHash> seen_;  // blocks whose sites were taken
    std::unordered_map<BlockKey, int, BlockKeyHash> unfinished_;  // rings still to lift per block
    std::deque<std::pair<BlockKey, Ring>> queue_;
    std::vector<Ring> rings_;
    bool stopping_ = false;
    std::thread worker_;
};

}  // namespace terrasynth::game
