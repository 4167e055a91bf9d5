#include "synth/coherence_fields.h"

namespace terrasynth::synth {
namespace {

uint8_t codeAt(const CoherenceMap& map, int level, int64_t gx, int64_t gy) {
    const int64_t size = int64_t(1) << level;
    const int64_t x0 = gx * size, y0 = gy * size;
    if (x0 + size <= map.x || y0 + size <= map.y || x0 >= map.x + map.width || y0 >= map.y + map.height)
        return static_cast<uint8_t>(map.outside);
    if (level == 0) return static_cast<uint8_t>(map.weights[static_cast<size_t>(gy - map.y) * map.width + (gx - map.x)]);
    int counts[3] = {0, 0, 0};
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) ++counts[codeAt(map, level - 1, 2 * gx + dx, 2 * gy + dy)];
    if (counts[0] > 0) return static_cast<uint8_t>(Coherence::Frozen);  // freezing is dominant
    return static_cast<uint8_t>(counts[1] > counts[2] ? Coherence::Coherent : Coherence::Free);
}

}  // namespace


std::vector<uint8_t> coherenceCodes(const CoherenceMap* map, int level, const LevelRegion& region) {
    std::vector<uint8_t> codes(region.pixels(), static_cast<uint8_t>(Coherence::Coherent));
    if (!map) return codes;
    for (int y = 0; y < region.height; ++y)
        for (int x = 0; x < region.width; ++x)
            codes[static_cast<size_t>(y) * region.width + x] = codeAt(*map, level, region.x + x, region.y + y);
    return codes;
}

PassHistory previousPass(const SynthesisHistory* history, int level, int pass, const LevelRegion& region) {
    PassHistory out;
    if (!history || level >= static_cast<int>(history->levels.size())) return out;
    const SynthesisHistory::Level& l = history->levels[level];
    if (pass >= static_cast<int>(l.passes.size()) || l.width == 0) return out;
    const SynthesisHistory::Pass& p = l.passes[pass];
    out.index.assign(region.pixels(), kNoPrevious);
    out.v.assign(region.pixels(), 0.0f);
    for (int y = 0; y < region.height; ++y) {
        const int hy = region.y + y - l.y;
        if (hy < 0 || hy >= l.height) continue;
        for (int x = 0; x < region.width; ++x) {
            const int hx = region.x + x - l.x;
            if (hx < 0 || hx >= l.width) continue;
            const size_t from = static_cast<size_t>(hy) * l.width + hx, to = static_cast<size_t>(y) * region.width + x;
            out.index[to] = p.index[from];
            out.v[to] = p.v[from];
        }
    }
    return out;
}

}  // namespace terrasynth::synth

namespace terrasynth {

size_t SynthesisHistory::memoryBytes() const {
    size_t total = 0;
    for (const Level& l : levels)
        for (const Pass& p : l.passes) total += p.index.size() * sizeof(uint32_t) + p.v.size() * sizeof(float);
    return total;
}

}  // namespace terrasynth
