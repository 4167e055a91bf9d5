#include "synth/initial_patches.h"

#include <algorithm>

namespace terrasynth::synth {

int automaticCoarsestLevel(const ExemplarDatabase& db) {
    const std::vector<AtlasRect>& base = db.levels[0].rects;
    size_t total = 0;
    for (const AtlasRect& r : base) total += static_cast<size_t>(r.width) * r.height;
    for (int level = db.levelCount() - 1; level > 0; --level) {
        size_t large = 0;
        const std::vector<AtlasRect>& rects = db.levels[level].rects;
        for (size_t e = 0; e < rects.size() && e < base.size(); ++e)
            if (std::min(rects[e].width, rects[e].height) >= kMinCoarsestSide)
                large += static_cast<size_t>(base[e].width) * base[e].height;
        if (2 * large >= total) return level;
    }
    return 0;
}

std::vector<uint32_t> cumulativeInteriorAreas(const DatabaseLevel& level) {
    std::vector<uint64_t> running;
    uint64_t total = 0;
    for (const AtlasRect& r : level.rects) {
        const int w = r.width - 2 * kInteriorMargin, h = r.height - 2 * kInteriorMargin;
        total += w > 0 && h > 0 ? static_cast<uint64_t>(w) * static_cast<uint64_t>(h) : 0;
        running.push_back(total);
    }
    int shift = 0;
    while ((total >> shift) >= (uint64_t(1) << 31)) ++shift;
    std::vector<uint32_t> out;
    for (uint64_t v : running) out.push_back(static_cast<uint32_t>(v >> shift));
    return out;
}

}  // namespace terrasynth::synth
