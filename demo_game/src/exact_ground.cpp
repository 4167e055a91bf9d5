// Exact ground: the mesh's triangle surface over level-0 samples, from the source or from cached blocks.
#include "terrasynth_game/exact_ground.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "terrasynth/mesh.h"

namespace terrasynth::game {
namespace {

// A fetch per block takes a few to tens of ms of synthesis; the frame loop must keep its CPU.
constexpr int kWorkerNice = 5;

}  // namespace

GroundSample groundOnCell(double nw, double ne, double sw, double se, double fu, double fw, double spacing) {
    GroundSample g;
    g.height_m = heightOnGridCell(nw, ne, sw, se, fu, fw);
    // Slopes of the triangle under the point (see heightOnGridCell for the split).
    double dz_east, dz_south;
    if (fu + fw <= 1.0) {
        dz_east = (ne - nw) / spacing;
        dz_south = (sw - nw) / spacing;
    } else {
        dz_east = (se - sw) / spacing;
        dz_south = (se - ne) / spacing;
    }
    // Rows grow south, so the northward slope is minus the southward one.
    const double nx = -dz_east, ny = dz_south, inv = 1.0 / std::sqrt(nx * nx + ny * ny + 1.0);
    g.normal[0] = nx * inv;
    g.normal[1] = ny * inv;
    g.normal[2] = inv;
    return g;
}

Result<GroundSample> exactGroundSample(const HeightSource& source, double mpp, double wx, double wy) {
    const double px = wx / mpp, py = -wy / mpp;
    const int64_t x0 = static_cast<int64_t>(std::floor(px)), y0 = static_cast<int64_t>(std::floor(py));
    auto cell = source({x0, y0, 2, 2}, 0);
    if (!cell) return cell.status();
    const Heightfield& c = *cell;
    return groundOnCell(c.at(0, 0), c.at(1, 0), c.at(0, 1), c.at(1, 1), px - x0, py - y0, mpp);
}

GroundCache::GroundCache(HeightSource source, double meters_per_pixel, size_t max_blocks)
    : source_(std::move(source)), meters_per_pixel_(meters_per_pixel), max_blocks_(std::max<size_t>(max_blocks, 16)) {
    TERRASYNTH_REQUIRE(meters_per_pixel > 0.0, "meters_per_pixel must be positive");
    worker_ = std::thread([this] { workerLoop(); });
}

GroundCache::~GroundCache() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    worker_.join();
}

BlockKey GroundCache::blockOf(int level, int64_t px, int64_t py) {
    return {level, floorDiv(px, kBlock), floorDiv(py, kBlock)};
}

std::vector<BlockKey> GroundCache::blocksAround(int level, double wx, double wy, double radius_m) const {
    const double s = std::ldexp(meters_per_pixel_, level), span = s * kBlock;
    const double px = wx / s, py = -wy / s, r = radius_m / s;
    const BlockKey lo = blockOf(level, static_cast<int64_t>(std::floor(px - r)), static_cast<int64_t>(std::floor(py - r)));
    const BlockKey hi = blockOf(level, static_cast<int64_t>(std::floor(px + r)), static_cast<int64_t>(std::floor(py + r)));
    std::vector<std::pair<double, BlockKey>> keys;
    for (int64_t by = lo.by; by <= hi.by; ++by)
        for (int64_t bx = lo.bx; bx <= hi.bx; ++bx) {
            // Distance from the point to the block's square (world metres).
            const double x0 = bx * span, x1 = x0 + span, y1 = -by * span, y0 = y1 - span;
            const double dx = std::max({x0 - wx, 0.0, wx - x1}), dy = std::max({y0 - wy, 0.0, wy - y1});
            const double d = std::hypot(dx, dy);
            if (d <= radius_m) keys.push_back({d, {level, bx, by}});
        }
    std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<BlockKey> out;
    out.reserve(keys.size());
    for (const auto& k : keys) out.push_back(k.second);
    return out;
}

void GroundCache::want(std::vector<BlockKey> keys) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        wanted_ = std::move(keys);
        ++want_tick_;
        for (const BlockKey& k : wanted_)
            if (auto it = blocks_.find(k); it != blocks_.end()) it->second.last_wanted = want_tick_;
    }
    wake_.notify_one();
}

bool GroundCache::idle() const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const BlockKey& k : wanted_)
        if (!blocks_.count(k) && !failed_.count(k)) return false;
    return true;
}

std::shared_ptr<const Heightfield> GroundCache::block(const BlockKey& key) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = blocks_.find(key);
    return it == blocks_.end() ? nullptr : it->second.field;
}

std::optional<GroundSample> GroundCache::sample(double wx, double wy) const {
    const double px = wx / meters_per_pixel_, py = -wy / meters_per_pixel_;
    const int64_t x0 = static_cast<int64_t>(std::floor(px)), y0 = static_cast<int64_t>(std::floor(py));
    const BlockKey key = blockOf(0, x0, y0);
    const std::shared_ptr<const Heightfield> b = block(key);
    if (!b) return std::nullopt;
    // The block has kBlock + 1 samples per side, so the cell's four corners are all in it.
    const int i = static_cast<int>(x0 - key.bx * kBlock), j = static_cast<int>(y0 - key.by * kBlock);
    return groundOnCell(b->at(i, j), b->at(i + 1, j), b->at(i, j + 1), b->at(i + 1, j + 1), px - x0, py - y0,
                        meters_per_pixel_);
}

Result<Heightfield> GroundCache::fetch(const BlockKey& key) const {
    return source_({key.bx * kBlock, key.by * kBlock, kBlock + 1, kBlock + 1}, key.level);
}

void GroundCache::workerLoop() {
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kWorkerNice);  // Linux: per thread
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
        std::optional<BlockKey> next;
        wake_.wait(lock, [&] {
            if (stopping_) return true;
            for (const BlockKey& k : wanted_)
                if (!blocks_.count(k) && !failed_.count(k)) {
                    next = k;
                    return true;
                }
            return false;
        });
        if (stopping_) return;
        lock.unlock();
        const auto t0 = std::chrono::steady_clock::now();
        Result<Heightfield> fetched = fetch(*next);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        lock.lock();
        if (!fetched) {
            failed_[*next] = fetched.message();
            stats_.last_error = fetched.message();
            ++stats_.failed;
            continue;
        }
        const bool still_wanted = std::find(wanted_.begin(), wanted_.end(), *next) != wanted_.end();
        blocks_[*next] = {std::make_shared<const Heightfield>(std::move(*fetched)), still_wanted ? want_tick_ : 0};
        ++stats_.fetched;
        fetch_ms_sum_ += ms;
        stats_.max_fetch_ms = std::max(stats_.max_fetch_ms, ms);
        // Least recently wanted blocks go first; the current list is never evicted.
        while (blocks_.size() > max_blocks_) {
            auto oldest = std::min_element(blocks_.begin(), blocks_.end(), [](const auto& a, const auto& b) {
                return a.second.last_wanted < b.second.last_wanted;
            });
            if (oldest->second.last_wanted >= want_tick_) break;
            blocks_.erase(oldest);
        }
    }
}

GroundCache::Stats GroundCache::stats() const {
    std::lock_guard<std::mutex> lock(mutex_);
    Stats s = stats_;
    s.cached = blocks_.size();
    s.mean_fetch_ms = stats_.fetched ? fetch_ms_sum_ / static_cast<double>(stats_.fetched) : 0.0;
    return s;
}

}  // namespace terrasynth::game
