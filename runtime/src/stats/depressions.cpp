// Public depression filling and the closed-pit mask.
#include "stats/field_check.h"
#include "stats/priority_flood.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth {

Heightfield fillDepressions(const Heightfield& field, bool epsilon) {
    stats::requireField(field);
    Heightfield filled = field;
    stats::priorityFlood(filled.heights, filled.width, filled.height, epsilon);
    return filled;
}

std::vector<uint8_t> pitMask(const Heightfield& field) {
    stats::requireField(field);
    std::vector<uint8_t> mask(field.size(), 0);
    for (int y = 1; y + 1 < field.height; ++y)
        for (int x = 1; x + 1 < field.width; ++x) {
            const float c = field.at(x, y);
            bool pit = true;
            for (int dy = -1; dy <= 1 && pit; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if ((dx || dy) && field.at(x + dx, y + dy) <= c) {
                        pit = false;
                        break;
                    }
            mask[static_cast<size_t>(y) * field.width + x] = pit ? 1 : 0;
        }
    return mask;
}

}  // namespace terrasynth
