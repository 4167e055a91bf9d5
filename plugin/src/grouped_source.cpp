// groupedSource (terrasynth_plugin/height_source.h): tile windows cut from one synthesis of the
// aligned group of tiles around them.
//
// Why: a synthesized window pays margins fixed in pixels at every level (synth/synthesis_plan.h),
// and with drainage by breaching those margins grow by twice each level's search radius: a 64^2
// tile cost 7.7 times its synthesis without drainage, a 256^2 one 3.0 times (docs/benchmarks.md,
// "Drainage cost"). Neighbouring tiles compute the same coarse pixels again. One window over a
// group of 4 x 4 tiles pays the margins once; by the source contract (grid.h: overlapping windows
// are bit-identical) its samples are the tiles' own.
#include <algorithm>
#include <future>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "terrasynth_plugin/height_source.h"

namespace terrasynth::plugin {
namespace {

// Samples around a group's own square that its window also holds, so a tile's shared last
// sample and the apron the tile builder reads around it (tileReadWindow: mesh step) stay inside.
constexpr int kGroupPad = 8;
// tileGroupedSource: groups of 4 x 4 tiles up to this side in samples, 2 x 2 above it (a 256-quad
// tile's group of 16 would synthesize 1041^2 for a view that may need few of them); tiles of this
// many quads or more are left alone (their margins are a small share); groups kept within this
// much memory (at least 8).
constexpr int kGroupSide = 512;
constexpr int kLargestGroupedTile = 1024;
constexpr size_t kGroupCacheBytes = size_t{64} << 20;

struct GroupKey {
    int level;
    int64_t gx, gy;
    bool operator<(const GroupKey& o) const { return std::tie(level, gx, gy) < std::tie(o.level, o.gx, o.gy); }
};

class Groups {
public:
    Groups(HeightSource base, int side, size_t capacity) : base_(std::move(base)), side_(side), capacity_(capacity) {}

    Result<Heightfield> heights(const PixelWindow& w, int level) {
        // Only windows of a tile's size (or its parent's half: tile_builder.cpp) that fit one group.
        const int64_t gx = floorDiv(w.x + kGroupPad, side_), gy = floorDiv(w.y + kGroupPad, side_);
        const PixelWindow group = growWindow({gx * side_, gy * side_, side_ + 1, side_ + 1}, kGroupPad);
        const bool tile_sized = w.width >= side_ / 8 && w.height >= side_ / 8;
        if (!tile_sized || intersectWindows(w, group) != w) return base_(w, level);
        std::shared_future<Result<Heightfield>> pending;
        std::promise<Result<Heightfield>> mine;
        bool compute = false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            const GroupKey key{level, gx, gy};
            auto found = index_.find(key);
            if (found != index_.end()) {
                order_.splice(order_.begin(), order_, found->second);  // most recently used first
                pending = found->second->second;
            } else {
                pending = mine.get_future().share();
                order_.emplace_front(key, pending);
                index_[key] = order_.begin();
                compute = true;
                while (order_.size() > capacity_) {  // waiters hold their own future
                    index_.erase(order_.back().first);
                    order_.pop_back();
                }
            }
        }
        if (compute) {
            try {
                mine.set_value(base_(group, level));
            } catch (...) {  // waiters must not be left without a value; the window tries alone below
                mine.set_value(Status::error("tile group failed"));
            }
        }
        const Result<Heightfield>& whole = pending.get();
        if (!whole) return base_(w, level);  // the window's own error, or its heights if only the group failed
        const Heightfield& g = whole.value();
        Heightfield out(w.width, w.height, g.meters_per_pixel_x);
        out.meters_per_pixel_y = g.meters_per_pixel_y;
        const int64_t ox = w.x - group.x, oy = w.y - group.y;
        for (int y = 0; y < w.height; ++y)
            std::copy_n(g.heights.begin() + static_cast<ptrdiff_t>((oy + y) * g.width + ox), w.width,
                        out.heights.begin() + static_cast<ptrdiff_t>(y) * w.width);
        return out;
    }

private:
    HeightSource base_;
    const int side_;
    const size_t capacity_;
    std::mutex mutex_;
    using Entry = std::pair<GroupKey, std::shared_future<Result<Heightfield>>>;
    std::list<Entry> order_;
    std::map<GroupKey, std::list<Entry>::iterator> index_;
};

}  // namespace

HeightSource groupedSource(HeightSource base, int group_side, size_t max_groups) {
    if (group_side < 8 || max_groups == 0) return base;
    auto groups = std::make_shared<Groups>(std::move(base), group_side, max_groups);
    return [groups](const PixelWindow& w, int level) { return groups->heights(w, level); };
}

HeightSource tileGroupedSource(HeightSource base, int tile_size) {
    if (tile_size >= kLargestGroupedTile) return base;
    const int side = std::min(4 * tile_size, std::max(kGroupSide, 2 * tile_size));
    const size_t group_bytes = sizeof(float) * static_cast<size_t>(side + 2 * kGroupPad + 1) * (side + 2 * kGroupPad + 1);
    return groupedSource(std::move(base), side, std::max<size_t>(8, kGroupCacheBytes / group_bytes));
}

}  // namespace terrasynth::plugin
