// Ready-made sources for exportGltf: a heightfield in memory, and types from a coordinate map.
#include <algorithm>
#include <memory>

#include "terrasynth/gltf_export.h"

namespace terrasynth {

HeightSource heightSourceFromField(Heightfield field) {
    auto shared = std::make_shared<const Heightfield>(std::move(field));
    return [shared](const PixelWindow& window, int level) -> Result<Heightfield> {
        if (level != 0) return Status::error("an in-memory heightfield has only level 0");
        if (window.width < 1 || window.height < 1) return Status::error("empty window");
        const Heightfield& f = *shared;
        Heightfield out(window.width, window.height, f.meters_per_pixel_x);
        out.meters_per_pixel_y = f.meters_per_pixel_y;
        for (int y = 0; y < window.height; ++y) {
            const int64_t sy = std::clamp<int64_t>(window.y + y, 0, f.height - 1);
            for (int x = 0; x < window.width; ++x) {
                const int64_t sx = std::clamp<int64_t>(window.x + x, 0, f.width - 1);
                out.at(x, y) = f.at(static_cast<int>(sx), static_cast<int>(sy));
            }
        }
        return out;
    };
}

std::vector<uint8_t> typesFromSources(const std::vector<uint8_t>& source_exemplar,
                                      const std::vector<int>& exemplar_type) {
    std::vector<uint8_t> types(source_exemplar.size(), 255);
    for (size_t i = 0; i < source_exemplar.size(); ++i) {
        const size_t e = source_exemplar[i];
        if (e < exemplar_type.size() && exemplar_type[e] >= 0 && exemplar_type[e] < 255)
            types[i] = static_cast<uint8_t>(exemplar_type[e]);
    }
    return types;
}

}  // namespace terrasynth
