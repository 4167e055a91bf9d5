// Rings along ridgelines: sites from coarse heights and the seed, lifted above the level-0 ground.
#include "terrasynth_game/rings.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "terrasynth/mesh.h"

namespace terrasynth::game {
namespace {

constexpr int kAxes[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
constexpr double kMinProminence = 12.0;  // metres above the 8 neighbours' mean, at kRingLevel
constexpr int kLiftWindow = 7;          // level-0 samples per side read under a ring
constexpr double kRingSearch = 30000.0; // metres around the player whose ring blocks are wanted

uint64_t mixHash(uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    return h ^ (h >> 33);
}

uint64_t siteHash(uint32_t seed, const BlockKey& key, int i, int j) {
    uint64_t h = mixHash(seed + 0x9E3779B97F4A7C15ull);
    h = mixHash(h ^ static_cast<uint64_t>(key.bx));
    h = mixHash(h ^ static_cast<uint64_t>(key.by));
    return mixHash(h ^ (static_cast<uint64_t>(i) << 32 | static_cast<uint32_t>(j)));
}

}  // namespace

std::vector<Ring> ridgeSites(const Heightfield& b, const BlockKey& key, double mpp, uint32_t seed) {
    struct Site {
        uint64_t rank;
        int i, j;
        double facing;
    };
    std::vector<Site> sites;
    const int n = b.width;
    // Interior samples only: the block's edge samples belong to its neighbours too.
    for (int j = 1; j < n - 1; ++j)
        for (int i = 1; i < n - 1; ++i) {
            const double h = b.at(i, j);
            double mean = 0.0;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) mean += (di || dj) ? b.at(i + di, j + dj) : 0.0;
            if (h - mean / 8.0 < kMinProminence) continue;
            int crests = 0, along = 0;
            double least_fall = 1e30;
            for (int a = 0; a < 4; ++a) {
                const double fall = 2.0 * h - b.at(i + kAxes[a][0], j + kAxes[a][1]) - b.at(i - kAxes[a][0], j - kAxes[a][1]);
                const bool crest = h > b.at(i + kAxes[a][0], j + kAxes[a][1]) && h > b.at(i - kAxes[a][0], j - kAxes[a][1]);
                crests += crest;
                if (fall < least_fall) {
                    least_fall = fall;
                    along = a;
                }
            }
            if (crests < 2) continue;
            // Axis (di, dj) in pixels (x east, y south) to a heading clockwise from north.
            const double facing = std::atan2(static_cast<double>(kAxes[along][0]), -static_cast<double>(kAxes[along][1]));
            sites.push_back({siteHash(seed, key, i, j), i, j, facing});
        }
    std::sort(sites.begin(), sites.end(), [](const Site& a, const Site& b) { return a.rank < b.rank; });
    std::vector<Ring> rings;
    const double spacing = std::ldexp(mpp, key.level);
    for (const Site& s : sites) {
        if (static_cast<int>(rings.size()) >= kRingsPerBlock) break;
        const int64_t gx = key.bx * GroundCache::kBlock + s.i, gy = key.by * GroundCache::kBlock + s.j;
        bool far_enough = true;
        for (const Ring& r : rings)
            far_enough = far_enough && std::hypot(r.x - gx * spacing, r.y + gy * spacing) >= kMinSpacing * spacing;
        if (!far_enough) continue;
        Ring ring;
        ring.id = (static_cast<uint64_t>(gx) & 0xffffffffull) << 32 | (static_cast<uint64_t>(gy) & 0xffffffffull);
        ring.x = gx * spacing;
        ring.y = -gy * spacing;
        ring.z = b.at(s.i, s.j);
        ring.facing = s.facing;
        rings.push_back(ring);
    }
    return rings;
}

bool passesThrough(const Ring& r, double x0, double y0, double z0, double x1, double y1, double z1) {
    const double nx = std::sin(r.facing), ny = std::cos(r.facing);
    const double d0 = (x0 - r.x) * nx + (y0 - r.y) * ny, d1 = (x1 - r.x) * nx + (y1 - r.y) * ny;
    if ((d0 > 0.0) == (d1 > 0.0) || d0 == d1) return false;
    const double t = d0 / (d0 - d1);
    const double px = x0 + t * (x1 - x0) - r.x, py = y0 + t * (y1 - y0) - r.y, pz = z0 + t * (z1 - z0) - r.z;
    return px * px + py * py + pz * pz <= r.radius_m * r.radius_m;
}

RingField::RingField(HeightSource source, double meters_per_pixel, uint32_t seed, double clearance_m)
    : source_(std::move(source)), meters_per_pixel_(meters_per_pixel), seed_(seed), clearance_m_(clearance_m) {
    worker_ = std::thread([this] { workerLoop(); });
}

RingField::~RingField() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

std::vector<BlockKey> RingField::blocksAround(const GroundCache& ground, double x, double y) const {
    return ground.blocksAround(kRingLevel, x, y, kRingSearch);
}

void RingField::update(const GroundCache& ground, const std::vector<BlockKey>& blocks) {
    std::vector<std::pair<BlockKey, std::shared_ptr<const Heightfield>>> fresh;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const BlockKey& k : blocks)
            if (!seen_.count(k))
                if (auto b = ground.block(k)) fresh.emplace_back(k, b);
    }
    if (fresh.empty()) return;
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [key, block] : fresh) {
        if (!seen_.insert(key).second) continue;
        const std::vector<Ring> sites = ridgeSites(*block, key, meters_per_pixel_, seed_);
        unfinished_[key] = static_cast<int>(sites.size());
        for (const Ring& r : sites) queue_.emplace_back(key, r);
    }
    wake_.notify_one();
}

bool RingField::ready(const std::vector<BlockKey>& blocks) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const BlockKey& k : blocks) {
        if (!seen_.count(k)) return false;
        auto it = unfinished_.find(k);
        if (it != unfinished_.end() && it->second > 0) return false;
    }
    return true;
}

std::vector<Ring> RingField::ringsNear(double x, double y, double radius_m) const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Ring> out;
    for (const Ring& r : rings_)
        if (std::hypot(r.x - x, r.y - y) <= radius_m) out.push_back(r);
    return out;
}

size_t RingField::ringCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return rings_.size();
}

void RingField::workerLoop() {
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 5);  // like GroundCache's worker
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        auto [key, ring] = queue_.front();
        queue_.pop_front();
        lock.unlock();
        // The highest level-0 sample within the ring's radius decides its height.
        const int64_t px = std::llround(ring.x / meters_per_pixel_), py = std::llround(-ring.y / meters_per_pixel_);
        const int half = kLiftWindow / 2;
        Result<Heightfield> under = source_({px - half, py - half, kLiftWindow, kLiftWindow}, 0);
        if (under) {
            const auto& h = under->heights;
            ring.z = *std::max_element(h.begin(), h.end()) + clearance_m_ + ring.radius_m;
        } else {
            ring.z += 400.0;  // no heights: keep it well clear (only a failing source gets here)
        }
        lock.lock();
        rings_.push_back(ring);
        --unfinished_[key];
    }
}

}  // namespace terrasynth::game
