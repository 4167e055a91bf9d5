// The data model's readers: hashing and comparing samples, the surface between them, the samples a
// child morphs to.
#include "tile_data.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "terrasynth/mesh.h"

namespace terrasynth::plugin {
namespace {
constexpr uint64_t kFnvPrime = 1099511628211ull;
}  // namespace

uint64_t hashHeights(const Heightfield& field) {
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * kFnvPrime;
    };
    mix(&field.width, sizeof field.width);
    mix(&field.height, sizeof field.height);
    mix(field.heights.data(), field.heights.size() * sizeof(float));
    return h;
}

uint64_t hashTileData(const Heightfield& heights, const std::vector<uint8_t>& types) {
    uint64_t h = hashHeights(heights);
    for (uint8_t id : types) h = (h ^ id) * kFnvPrime;
    return h;
}

bool sameSamples(const TileData& a, const TileData& b) {
    return a.hash == b.hash && a.heights.width == b.heights.width && a.heights.height == b.heights.height &&
           std::memcmp(a.heights.heights.data(), b.heights.heights.data(), a.heights.heights.size() * sizeof(float)) == 0 &&
           a.types == b.types;
}

float surfaceHeight(const TileData& tile, double wx, double wy) {
    // Mesh vertex (i, j) is tile sample (i * step, j * step).
    const int step = tile.mesh_step;
    const int n = tile.tileSize() / step + 1;
    const double step_m = tile.spacing_m * step;
    const double u = (wx - tile.west_x) / step_m, w = (tile.north_y - wy) / step_m;
    const int i = std::clamp(static_cast<int>(std::floor(u)), 0, n - 2);
    const int j = std::clamp(static_cast<int>(std::floor(w)), 0, n - 2);
    auto vertex = [&](int col, int row) { return tile.sample(col * step, row * step); };
    const double fu = std::clamp(u - i, 0.0, 1.0), fw = std::clamp(w - j, 0.0, 1.0);
    return static_cast<float>(
        heightOnGridCell(vertex(i, j), vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1), fu, fw));
}

Heightfield parentSamples(const TileData& parent, const TileKey& child) {
    TERRASYNTH_REQUIRE(child.parent() == parent.key, "parentSamples: not the child's parent");
    const int half = parent.tileSize() / 2;
    // The child's quadrant of the parent: its north-west sample in the parent's tile samples.
    const int x0 = static_cast<int>(child.x - 2 * parent.key.x) * half;
    const int y0 = static_cast<int>(child.y - 2 * parent.key.y) * half;
    Heightfield out(half + 1, half + 1, parent.spacing_m);
    for (int row = 0; row <= half; ++row)
        for (int col = 0; col <= half; ++col) out.at(col, row) = parent.sample(x0 + col, y0 + row);
    return out;
}

}  // namespace terrasynth::plugin
