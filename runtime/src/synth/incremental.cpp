// Local re-synthesis after an edit (s5.3): Free inside the edit, Coherent in a band, Frozen beyond.
// Frozen pixels do not depend on their neighbours, so a window reaching a synthesis margin beyond
// the band computes exactly what a full re-synthesis with the same weights would.
#include "terrasynth/incremental.h"

#include <algorithm>

#include "synth/synthesis_plan.h"

namespace terrasynth {
namespace {

PixelWindow intersect(const PixelWindow& a, const PixelWindow& b) {
    const int64_t x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
    const int64_t x1 = std::min(a.x + a.width, b.x + b.width), y1 = std::min(a.y + a.height, b.y + b.height);
    if (x1 <= x0 || y1 <= y0) return {x0, y0, 0, 0};
    return {x0, y0, static_cast<int>(x1 - x0), static_cast<int>(y1 - y0)};
}

PixelWindow grow(const PixelWindow& w, int by) { return {w.x - by, w.y - by, w.width + 2 * by, w.height + 2 * by}; }

// Copies the window's history into the extent's, level by level, pass by pass, by global position.
// Only the window's valid part at each level (its region minus the margin) is trusted.
void mergeHistory(SynthesisHistory& into, const SynthesisHistory& update, int margin) {
    for (size_t level = 0; level < update.levels.size() && level < into.levels.size(); ++level) {
        const auto& from = update.levels[level];
        auto& to = into.levels[level];
        if (from.width == 0 || to.width == 0) continue;
        for (size_t pass = 0; pass < from.passes.size() && pass < to.passes.size(); ++pass) {
            for (int y = margin; y < from.height - margin; ++y) {
                const int ty = from.y + y - to.y;
                if (ty < 0 || ty >= to.height) continue;
                for (int x = margin; x < from.width - margin; ++x) {
                    const int tx = from.x + x - to.x;
                    if (tx < 0 || tx >= to.width) continue;
                    const size_t f = static_cast<size_t>(y) * from.width + x, t = static_cast<size_t>(ty) * to.width + tx;
                    to.passes[pass].index[t] = from.passes[pass].index[f];
                    to.passes[pass].v[t] = from.passes[pass].v[f];
                }
            }
        }
    }
}

}  // namespace

Result<IncrementalTerrain> IncrementalTerrain::create(Synthesizer& synthesizer, const PixelWindow& extent,
                                                      SynthesisParams params) {
    IncrementalTerrain terrain(synthesizer, extent, std::move(params));
    terrain.params_.record_history = true;
    terrain.params_.previous.reset();
    terrain.params_.coherence.reset();
    auto out = synthesizer.synthesize(extent, terrain.params_, 0, false);
    if (!out) return out.status();
    terrain.heights_ = std::move(out->heights);
    terrain.history_ = std::move(out->history);
    terrain.last_window_ = extent;
    return terrain;
}

Status IncrementalTerrain::update(std::shared_ptr<const SynthesisConstraints> constraints, const PixelWindow& changed) {
    const PixelWindow band = grow(changed, kCoherentBand);
    // Frozen pixels reached by the window's own margin (2 pixels per subpass at level 0) settle
    // the band's neighbourhoods exactly as a full synthesis would.
    const PixelWindow window = intersect(grow(band, synth::kSubpassReach * 4 * params_.correction_passes), extent_);
    if (window.width == 0) return Status::ok();
    auto map = std::make_shared<CoherenceMap>();
    map->x = window.x, map->y = window.y, map->width = window.width, map->height = window.height;
    map->outside = Coherence::Frozen;
    map->weights.assign(static_cast<size_t>(window.width) * window.height, Coherence::Frozen);
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x) {
            const int64_t gx = window.x + x, gy = window.y + y;
            auto inside = [&](const PixelWindow& w) { return gx >= w.x && gy >= w.y && gx < w.x + w.width && gy < w.y + w.height; };
            map->weights[static_cast<size_t>(y) * window.width + x] =
                inside(changed) ? Coherence::Free : (inside(band) ? Coherence::Coherent : Coherence::Frozen);
        }
    SynthesisParams params = params_;
    params.constraints = std::move(constraints);
    params.previous = history_;
    params.coherence = map;
    params.record_history = true;
    auto out = synthesizer_->synthesize(window, params, 0, false);
    if (!out) return out.status();
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x)
            heights_.at(static_cast<int>(window.x - extent_.x) + x, static_cast<int>(window.y - extent_.y) + y) =
                out->heights.at(x, y);
    // The synthesis has finished reading the history, and nothing else holds it: merge in place.
    params.previous.reset();
    mergeHistory(*history_, *out->history, synth::kSubpassReach * 4 * params_.correction_passes);
    params_.constraints = params.constraints;
    last_window_ = window;
    return Status::ok();
}

}  // namespace terrasynth
