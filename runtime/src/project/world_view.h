// Private: heights of any window and level of a project's world, for Terrain and for the edit
// session's snapshots (one definition, so what the editor shows is what the plugin and the CLI read).
//
// The world is the reference synthesis (windowed and deterministic, so unbounded and seamless) with
// the project's extent replaced at level 0 by its edited heights. Coarser levels add the mean of the
// edit (edited - reference) over each sample's 2^level x 2^level block of level-0 pixels (the part
// outside the extent counts as 0), so a coarse tile looks like the fine tiles under it and meets the
// untouched world where the edit fades out. Reference windows are cached (most tile rebuilds after an
// edit ask for windows the cache already holds).
#pragma once

#include <atomic>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <vector>

#include "project/synthesizer_pool.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::project {

// The edited extent of one moment: immutable once built, shared by the tile workers reading it.
class ExtentEdit {
public:
    // `heights` and `reference`: level-0 heights over `extent`, row-major.
    ExtentEdit(PixelWindow extent, std::shared_ptr<const std::vector<float>> heights,
               std::shared_ptr<const std::vector<float>> reference);
    // The next moment of `previous` (same extent and reference), whose heights differ from it only
    // inside `changed` (global level-0 pixels). If `previous` already built its block sums, this one's
    // are its copy updated over `changed`, here on the calling thread (bit-identical to a full build,
    // which a tile worker would otherwise pay on its first coarse request: 25-75 ms for a 1024^2
    // extent on the 2-core machine while the editor drags, against about 2 ms for a point's window).
    ExtentEdit(PixelWindow extent, std::shared_ptr<const std::vector<float>> heights,
               std::shared_ptr<const std::vector<float>> reference, const ExtentEdit& previous, PixelWindow changed);
    const PixelWindow& extent() const { return extent_; }
    const std::vector<float>& heights() const { return *heights_; }
    const std::shared_ptr<const std::vector<float>>& heightsPtr() const { return heights_; }
    const std::shared_ptr<const std::vector<float>>& referencePtr() const { return reference_; }
    // Level 0: the edited heights where the window meets the extent. Coarser: + the block means of
    // the edit. `h` holds the reference synthesis of `window` at `level`. Thread-safe.
    void applyTo(Heightfield& h, const PixelWindow& window, int level) const;
    // The edited level-0 height at a whole pixel inside the extent.
    float at(int64_t x, int64_t y) const {
        return (*heights_)[static_cast<size_t>(y - extent_.y) * extent_.width + static_cast<size_t>(x - extent_.x)];
    }

    // Block sums of one level (public for world_view.cpp's helpers).
    struct Level {
        int64_t x = 0, y = 0;  // first sample (global, this level) touching the extent
        int width = 0, height = 0;
        std::vector<double> sums;  // sum of the edit over the block's extent pixels (empty at level 0)
    };

private:
    void buildSums() const;
    void updateSums(const ExtentEdit& previous, const PixelWindow& changed) const;
    PixelWindow extent_;
    std::shared_ptr<const std::vector<float>> heights_, reference_;
    mutable std::once_flag sums_once_;
    mutable std::atomic<bool> sums_ready_{false};  // levels_ complete (read by a later moment's update)
    mutable std::vector<Level> levels_;  // index = level; built on the first coarse request
};

class WorldView {
public:
    WorldView(std::shared_ptr<SynthesizerPool> pool, SynthesisParams reference);
    const SynthesisParams& reference() const { return reference_; }
    SynthesizerPool& pool() const { return *pool_; }

    // The world's heights of `window` at `level` with `edit` applied (null: the reference alone).
    // Sources (want_sources) are the reference synthesis's, also inside an edited extent.
    // Thread-safe: each thread synthesizes with its own synthesizer.
    Result<SynthesisOutput> synthesize(const PixelWindow& window, int level, bool want_sources,
                                       const ExtentEdit* edit) const;
    Result<Heightfield> heights(const PixelWindow& window, int level, const ExtentEdit* edit) const;
    // Bilinear level-0 height at fractional pixel (px, py). Thread-safe.
    Result<double> heightAt(double px, double py, const ExtentEdit* edit) const;

private:
    Result<Heightfield> referenceHeights(const PixelWindow& window, int level) const;
    std::shared_ptr<SynthesizerPool> pool_;
    SynthesisParams reference_;
    // LRU cache of reference windows (key: level, x, y, width, height).
    using Key = std::tuple<int, int64_t, int64_t, int, int>;
    static constexpr size_t kCacheBytes = size_t{96} << 20;
    mutable std::mutex cache_mutex_;
    mutable std::list<std::pair<Key, std::shared_ptr<const Heightfield>>> lru_;
    mutable std::map<Key, decltype(lru_)::iterator> cache_;
    mutable size_t cache_bytes_ = 0;
};

}  // namespace terrasynth::project
