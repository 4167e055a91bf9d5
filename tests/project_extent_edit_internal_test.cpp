// The edit session's block sums (project/world_view.h): a moment built from the previous one by
// updating only the changed window gives exactly the coarse heights of a full build, at every
// level, for extents at negative and odd global offsets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "project/world_view.h"

namespace terrasynth::project {
namespace {

std::shared_ptr<const std::vector<float>> randomPlane(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> height(-200.0f, 3000.0f);
    auto plane = std::make_shared<std::vector<float>>(n);
    for (float& v : *plane) v = height(rng);
    return plane;
}

// v / 2^level rounded down, written here rather than taken from the code under test.
int64_t floorDown(int64_t v, int level) { return v >= 0 ? v >> level : -((-v + (int64_t(1) << level) - 1) >> level); }

// What applyTo adds at `level` over a window one sample wider than the extent's blocks on each side.
std::vector<float> coarseEdit(const ExtentEdit& edit, int level) {
    const PixelWindow& e = edit.extent();
    auto down = [level](int64_t v) { return floorDown(v, level); };
    const int64_t x0 = down(e.x) - 1, y0 = down(e.y) - 1;
    const int w = static_cast<int>(down(e.x + e.width - 1) + 2 - x0), h = static_cast<int>(down(e.y + e.height - 1) + 2 - y0);
    Heightfield field(w, h, 1.0);
    edit.applyTo(field, {x0, y0, w, h}, level);
    return field.heights;
}

// The oracle: a block's sum of (edited - reference), recursively from its four children in
// row-major order (pixels outside the extent add nothing), then the mean added to a zero field.
double blockSum(const PixelWindow& e, const std::vector<float>& h, const std::vector<float>& r, int level, int64_t bx,
                int64_t by) {
    if (level == 0) {
        if (bx < e.x || by < e.y || bx >= e.x + e.width || by >= e.y + e.height) return 0.0;
        const size_t i = static_cast<size_t>(by - e.y) * e.width + static_cast<size_t>(bx - e.x);
        return static_cast<double>(h[i]) - static_cast<double>(r[i]);
    }
    double sum = 0.0;
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) sum += blockSum(e, h, r, level - 1, 2 * bx + dx, 2 * by + dy);
    return sum;
}

std::vector<float> oracleEdit(const PixelWindow& e, const std::vector<float>& h, const std::vector<float>& r, int level) {
    auto down = [level](int64_t v) { return floorDown(v, level); };
    const int64_t x0 = down(e.x) - 1, y0 = down(e.y) - 1;
    const int w = static_cast<int>(down(e.x + e.width - 1) + 2 - x0), hh = static_cast<int>(down(e.y + e.height - 1) + 2 - y0);
    std::vector<float> out(static_cast<size_t>(w) * hh, 0.0f);
    for (int y = 0; y < hh; ++y)
        for (int x = 0; x < w; ++x)
            out[static_cast<size_t>(y) * w + x] += static_cast<float>(blockSum(e, h, r, level, x0 + x, y0 + y) / std::ldexp(1.0, 2 * level));
    return out;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(ExtentEdit, UpdatedSumsMatchAFullBuildAtEveryLevel) {
    for (const PixelWindow extent : {PixelWindow{-37, 21, 300, 203}, PixelWindow{0, 0, 256, 256}, PixelWindow{5, -9, 97, 61}}) {
        const size_t n = static_cast<size_t>(extent.width) * extent.height;
        auto reference = randomPlane(n, 1);
        auto before = randomPlane(n, 2);
        ExtentEdit previous(extent, before, reference);
        (void)coarseEdit(previous, 1);  // builds the previous moment's sums, as a coarse tile would

        // Three successive edits: a small window, one on the extent's corner, and nothing changed.
        std::shared_ptr<const std::vector<float>> heights = before;
        std::unique_ptr<ExtentEdit> last;
        const ExtentEdit* prior = &previous;
        const PixelWindow changes[] = {{extent.x + 11, extent.y + 7, 23, 19},
                                       {extent.x + extent.width - 13, extent.y + extent.height - 6, 13, 6},
                                       {extent.x, extent.y, 0, 0}};
        uint32_t seed = 10;
        for (const PixelWindow& changed : changes) {
            auto next = std::make_shared<std::vector<float>>(*heights);
            std::mt19937 rng(seed++);
            std::uniform_real_distribution<float> height(-500.0f, 5000.0f);
            for (int64_t y = changed.y; y < changed.y + changed.height; ++y)
                for (int64_t x = changed.x; x < changed.x + changed.width; ++x)
                    (*next)[static_cast<size_t>(y - extent.y) * extent.width + static_cast<size_t>(x - extent.x)] = height(rng);
            heights = next;
            auto updated = std::make_unique<ExtentEdit>(extent, heights, reference, *prior, changed);
            const ExtentEdit full(extent, heights, reference);
            for (int level = 1; level <= 10; ++level)
                EXPECT_TRUE(sameBits(coarseEdit(*updated, level), coarseEdit(full, level)))
                    << "extent " << extent.x << "," << extent.y << " level " << level << " change " << changed.x;
            for (int level = 1; level <= 6; ++level)
                EXPECT_TRUE(sameBits(coarseEdit(full, level), oracleEdit(extent, *heights, *reference, level))) << level;
            last = std::move(updated);
            prior = last.get();
        }
    }
}

TEST(ExtentEdit, AMomentAfterOneWithoutSumsBuildsThemWhenAsked) {
    const PixelWindow extent{-3, -3, 130, 70};
    const size_t n = static_cast<size_t>(extent.width) * extent.height;
    auto reference = randomPlane(n, 3);
    const ExtentEdit previous(extent, randomPlane(n, 4), reference);  // sums never built
    auto heights = randomPlane(n, 5);
    const ExtentEdit next(extent, heights, reference, previous, extent);
    const ExtentEdit full(extent, heights, reference);
    for (int level = 1; level <= 8; ++level) EXPECT_TRUE(sameBits(coarseEdit(next, level), coarseEdit(full, level))) << level;
}

}  // namespace
}  // namespace terrasynth::project
