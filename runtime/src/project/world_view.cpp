#include "project/world_view.h"

#include <algorithm>
#include <cmath>

namespace terrasynth::project {

namespace {
// Floor division by 2^level for negative global coordinates too.
int64_t floorShift(int64_t v, int level) { return v >= 0 ? v >> level : -((-v + (int64_t(1) << level) - 1) >> level); }
}  // namespace

ExtentEdit::ExtentEdit(PixelWindow extent, std::shared_ptr<const std::vector<float>> heights,
                       std::shared_ptr<const std::vector<float>> reference)
    : extent_(extent), heights_(std::move(heights)), reference_(std::move(reference)) {
    const size_t n = static_cast<size_t>(extent_.width) * extent_.height;
    TERRASYNTH_REQUIRE(heights_ && heights_->size() == n, "edited heights must cover the extent");
    TERRASYNTH_REQUIRE(reference_ && reference_->size() == n, "reference heights must cover the extent");
}

ExtentEdit::ExtentEdit(PixelWindow extent, std::shared_ptr<const std::vector<float>> heights,
                       std::shared_ptr<const std::vector<float>> reference, const ExtentEdit& previous,
                       PixelWindow changed)
    : ExtentEdit(extent, std::move(heights), std::move(reference)) {
    if (previous.extent_ == extent_ && previous.reference_ == reference_ && previous.sums_ready_.load(std::memory_order_acquire))
        std::call_once(sums_once_, [&] { updateSums(previous, changed); });
}

namespace {

// Level 0 keeps no sums (its values are edited - reference, read from the planes), so a moment's
// copy of the previous sums is a third of the extent's size in doubles instead of 1.3x.
struct Level0 {
    const float* heights;
    const float* reference;
};

// The block (bx, by) of `coarse` as the sum of its 2x2 children in `fine` (those touching the
// extent), added in row-major order from 0: the same doubles whichever blocks are recomputed.
void sumChildren(const ExtentEdit::Level& fine, const Level0* planes, ExtentEdit::Level& coarse, int64_t bx, int64_t by) {
    double sum = 0.0;
    for (int64_t fy = 2 * by; fy <= 2 * by + 1; ++fy) {
        if (fy < fine.y || fy >= fine.y + fine.height) continue;
        for (int64_t fx = 2 * bx; fx <= 2 * bx + 1; ++fx) {
            if (fx < fine.x || fx >= fine.x + fine.width) continue;
            const size_t i = static_cast<size_t>(fy - fine.y) * fine.width + static_cast<size_t>(fx - fine.x);
            sum += planes ? static_cast<double>(planes->heights[i]) - static_cast<double>(planes->reference[i]) : fine.sums[i];
        }
    }
    coarse.sums[static_cast<size_t>(by - coarse.y) * coarse.width + static_cast<size_t>(bx - coarse.x)] = sum;
}

// Level `level` blocks covering the level-0 window `w`, clipped to the level's blocks.
void sumBlocks(const ExtentEdit::Level& fine, const Level0* planes, ExtentEdit::Level& coarse, int level,
               const PixelWindow& w) {
    const int64_t bx0 = std::max(coarse.x, floorShift(w.x, level)), by0 = std::max(coarse.y, floorShift(w.y, level));
    const int64_t bx1 = std::min(coarse.x + coarse.width - 1, floorShift(w.x + w.width - 1, level));
    const int64_t by1 = std::min(coarse.y + coarse.height - 1, floorShift(w.y + w.height - 1, level));
    for (int64_t by = by0; by <= by1; ++by)
        for (int64_t bx = bx0; bx <= bx1; ++bx) sumChildren(fine, planes, coarse, bx, by);
}

constexpr int kSumLevels = 13;

}  // namespace

// Sums of the edit per block, level by level from the 2x2 children (samples of each level that
// touch the extent), in double so the means do not depend on block size.
void ExtentEdit::buildSums() const {
    levels_.resize(kSumLevels);
    Level& base = levels_[0];
    base.x = extent_.x, base.y = extent_.y, base.width = extent_.width, base.height = extent_.height;
    const Level0 planes{heights_->data(), reference_->data()};
    for (int level = 1; level < kSumLevels; ++level) {
        const Level& fine = levels_[level - 1];
        Level& l = levels_[level];
        l.x = floorShift(fine.x, 1), l.y = floorShift(fine.y, 1);
        l.width = static_cast<int>(floorShift(fine.x + fine.width - 1, 1) - l.x + 1);
        l.height = static_cast<int>(floorShift(fine.y + fine.height - 1, 1) - l.y + 1);
        l.sums.assign(static_cast<size_t>(l.width) * l.height, 0.0);
        sumBlocks(fine, level == 1 ? &planes : nullptr, l, level, extent_);
    }
    sums_ready_.store(true, std::memory_order_release);
}

// The previous moment's sums with the blocks over `changed` recomputed (same geometry: same extent).
void ExtentEdit::updateSums(const ExtentEdit& previous, const PixelWindow& changed) const {
    levels_ = previous.levels_;
    const PixelWindow both = intersectWindows(changed, extent_);
    const Level0 planes{heights_->data(), reference_->data()};
    if (both.width > 0 && both.height > 0)
        for (int level = 1; level < kSumLevels; ++level)
            sumBlocks(levels_[level - 1], level == 1 ? &planes : nullptr, levels_[level], level, both);
    sums_ready_.store(true, std::memory_order_release);
}

void ExtentEdit::applyTo(Heightfield& h, const PixelWindow& window, int level) const {
    if (level == 0) {
        const PixelWindow both = intersectWindows(window, extent_);
        for (int64_t y = both.y; y < both.y + both.height; ++y)
            for (int64_t x = both.x; x < both.x + both.width; ++x)
                h.at(static_cast<int>(x - window.x), static_cast<int>(y - window.y)) = at(x, y);
        return;
    }
    std::call_once(sums_once_, [this] { buildSums(); });
    TERRASYNTH_REQUIRE(level < static_cast<int>(levels_.size()), "level beyond the edit pyramid");
    const Level& l = levels_[level];
    const PixelWindow both = intersectWindows(window, {l.x, l.y, l.width, l.height});
    const double block_area = std::ldexp(1.0, 2 * level);
    for (int64_t y = both.y; y < both.y + both.height; ++y)
        for (int64_t x = both.x; x < both.x + both.width; ++x) {
            const double sum = l.sums[static_cast<size_t>(y - l.y) * l.width + static_cast<size_t>(x - l.x)];
            h.at(static_cast<int>(x - window.x), static_cast<int>(y - window.y)) += static_cast<float>(sum / block_area);
        }
}

WorldView::WorldView(std::shared_ptr<SynthesizerPool> pool, SynthesisParams reference)
    : pool_(std::move(pool)), reference_(std::move(reference)) {
    reference_.record_history = false;
    reference_.previous.reset();
    reference_.coherence.reset();
}

Result<Heightfield> WorldView::referenceHeights(const PixelWindow& window, int level) const {
    const Key key{level, window.x, window.y, window.width, window.height};
    {
        std::lock_guard<std::mutex> lock(cache_mutex_);
        if (auto it = cache_.find(key); it != cache_.end()) {
            lru_.splice(lru_.begin(), lru_, it->second);
            return *it->second->second;
        }
    }
    auto synthesizer = pool_->forThisThread();
    if (!synthesizer) return synthesizer.status();
    auto out = synthesizer.value()->synthesize(window, reference_, level, false);
    if (!out) return out.status();
    auto stored = std::make_shared<const Heightfield>(std::move(out->heights));
    std::lock_guard<std::mutex> lock(cache_mutex_);
    if (cache_.find(key) == cache_.end()) {
        lru_.emplace_front(key, stored);
        cache_[key] = lru_.begin();
        cache_bytes_ += stored->heights.size() * sizeof(float);
        while (cache_bytes_ > kCacheBytes && lru_.size() > 1) {
            cache_bytes_ -= lru_.back().second->heights.size() * sizeof(float);
            cache_.erase(lru_.back().first);
            lru_.pop_back();
        }
    }
    return *stored;
}

Result<SynthesisOutput> WorldView::synthesize(const PixelWindow& window, int level, bool want_sources,
                                              const ExtentEdit* edit) const {
    SynthesisOutput out;
    const bool inside = edit && level == 0 && intersectWindows(window, edit->extent()) == window;
    if (want_sources) {
        auto synthesizer = pool_->forThisThread();
        if (!synthesizer) return synthesizer.status();
        auto full = synthesizer.value()->synthesize(window, reference_, level, true);
        if (!full) return full.status();
        out = std::move(full.value());
    } else if (inside) {
        // Level-0 windows inside the extent need no synthesis at all.
        out.heights = Heightfield(window.width, window.height, pool_->database().meters_per_pixel);
    } else {
        auto heights = referenceHeights(window, level);
        if (!heights) return heights.status();
        out.heights = std::move(heights.value());
    }
    if (edit) edit->applyTo(out.heights, window, level);
    return out;
}

Result<Heightfield> WorldView::heights(const PixelWindow& window, int level, const ExtentEdit* edit) const {
    auto out = synthesize(window, level, false, edit);
    if (!out) return out.status();
    return std::move(out->heights);
}

Result<double> WorldView::heightAt(double px, double py, const ExtentEdit* edit) const {
    if (!std::isfinite(px) || !std::isfinite(py) || std::fabs(px) > 1e15 || std::fabs(py) > 1e15)
        return Status::error("heightAt: position outside the world's grid");
    const double fx = std::floor(px), fy = std::floor(py);
    const int64_t x = static_cast<int64_t>(fx), y = static_cast<int64_t>(fy);
    const double tx = px - fx, ty = py - fy;
    float h00, h10, h01, h11;
    if (edit && intersectWindows({x, y, 2, 2}, edit->extent()) == PixelWindow{x, y, 2, 2}) {
        h00 = edit->at(x, y), h10 = edit->at(x + 1, y), h01 = edit->at(x, y + 1), h11 = edit->at(x + 1, y + 1);
    } else {
        auto h = heights({x, y, 2, 2}, 0, edit);
        if (!h) return h.status();
        h00 = h->at(0, 0), h10 = h->at(1, 0), h01 = h->at(0, 1), h11 = h->at(1, 1);
    }
    const double top = h00 + (h10 - h00) * tx, bottom = h01 + (h11 - h01) * tx;
    return top + (bottom - top) * ty;
}

}  // namespace terrasynth::project
