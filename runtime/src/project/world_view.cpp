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

// Sums of the edit per block, level by level from the 2x2 children (samples of each level that
// touch the extent), in double so the means do not depend on block size.
void ExtentEdit::buildSums() const {
    const int kLevels = 13;
    levels_.resize(kLevels);
    Level& base = levels_[0];
    base.x = extent_.x, base.y = extent_.y, base.width = extent_.width, base.height = extent_.height;
    base.sums.resize(heights_->size());
    for (size_t i = 0; i < base.sums.size(); ++i)
        base.sums[i] = static_cast<double>((*heights_)[i]) - static_cast<double>((*reference_)[i]);
    for (int level = 1; level < kLevels; ++level) {
        const Level& fine = levels_[level - 1];
        Level& l = levels_[level];
        l.x = floorShift(fine.x, 1), l.y = floorShift(fine.y, 1);
        l.width = static_cast<int>(floorShift(fine.x + fine.width - 1, 1) - l.x + 1);
        l.height = static_cast<int>(floorShift(fine.y + fine.height - 1, 1) - l.y + 1);
        l.sums.assign(static_cast<size_t>(l.width) * l.height, 0.0);
        for (int y = 0; y < fine.height; ++y)
            for (int x = 0; x < fine.width; ++x) {
                const int64_t cx = floorShift(fine.x + x, 1) - l.x, cy = floorShift(fine.y + y, 1) - l.y;
                l.sums[static_cast<size_t>(cy) * l.width + cx] += fine.sums[static_cast<size_t>(y) * fine.width + x];
            }
    }
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
