#include "synth/level_ground.h"

namespace terrasynth::synth {

std::vector<uint8_t> levelGroundFlags(const DatabaseLevel& db, float tolerance) {
    std::vector<uint8_t> flags(db.pixelCount(), 0);
    const float* e = db.height_m.data();
    for (int y = 1; y + 1 < db.height; ++y)
        for (int x = 1; x + 1 < db.width; ++x) {
            const int q = y * db.width + x;
            bool level = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) level = level && std::fabs(e[q + dy * db.width + dx] - e[q]) <= tolerance;
            flags[static_cast<size_t>(q)] = level ? 1 : 0;
        }
    return flags;
}

float lowestExemplarHeight(const DatabaseLevel& db) {
    float lowest = INFINITY;
    for (const AtlasRect& r : db.rects)
        for (int y = r.y; y < r.y + r.height; ++y)
            for (int x = r.x; x < r.x + r.width; ++x)
                lowest = std::fmin(lowest, db.height_m[static_cast<size_t>(y) * db.width + x]);
    return lowest;
}

const std::vector<uint8_t>& LevelGround::flags(const ExemplarDatabase& db, int level) {
    if (flags_.size() != db.levels.size()) flags_.assign(db.levels.size(), {}), known_.assign(db.levels.size(), 0);
    if (!known_[level]) flags_[level] = levelGroundFlags(db.levels[level], tolerance(db)), known_[level] = 1;
    return flags_[level];
}

float LevelGround::lowest(const ExemplarDatabase& db, int level) {
    if (lowest_.size() != db.levels.size()) lowest_.assign(db.levels.size(), 0.0f), lowest_known_.assign(db.levels.size(), 0);
    if (!lowest_known_[level]) lowest_[level] = lowestExemplarHeight(db.levels[level]), lowest_known_[level] = 1;
    return lowest_[level];
}

}  // namespace terrasynth::synth
