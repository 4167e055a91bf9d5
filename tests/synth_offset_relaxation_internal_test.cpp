// The offset relaxation (synth/offset_relaxation.h) on a real exemplar: a patch copied whole keeps
// its heights, the step where two patches of gentle ground meet closes while ground beyond the
// relaxation's reach stays put, fixed pixels keep their offsets bit for bit, and a pixel's result
// depends only on the state within the reach (a smaller region gives the same bits inside, which is
// what keeps windows bit-identical to larger windows; the larger region is relaxed in several bands).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "synth/offset_relaxation.h"
#include "test_support.h"

namespace terrasynth::synth {
namespace {

constexpr int kIterations = 16;

// The exemplar as a one-exemplar level (the relaxation reads only the heights and the atlas width).
DatabaseLevel exemplarLevel(const std::string& stem, double* spacing) {
    const Heightfield field = test::loadExemplarField(stem);
    DatabaseLevel level;
    level.width = field.width, level.height = field.height;
    level.height_m = field.heights;
    level.rects = {{0, 0, field.width, field.height}};
    *spacing = field.meters_per_pixel_x;
    return level;
}

// A region whose pixels copy the exemplar from (sx, sy) on, V = v, no ceiling.
std::vector<PixelState> patch(int width, int height, int sx, int sy, float v) {
    std::vector<PixelState> state(static_cast<size_t>(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            PixelState& s = state[static_cast<size_t>(y) * width + x];
            s.x = static_cast<float>(sx + x), s.y = static_cast<float>(sy + y), s.v = v, s.ceiling = INFINITY;
        }
    return state;
}

// `west` with its pixels from column `seam` on taken from `east` (both `width` wide): two patches
// meeting along a seam the exemplar does not have.
std::vector<PixelState> seamed(std::vector<PixelState> west, const std::vector<PixelState>& east, int width, int seam) {
    for (size_t i = 0; i < west.size(); ++i)
        if (static_cast<int>(i % width) >= seam) west[i] = east[i];
    return west;
}

float heightOf(const DatabaseLevel& level, const PixelState& s) {
    return level.height_m[static_cast<size_t>(std::lround(s.y)) * level.width + std::lround(s.x)] + s.v;
}

TEST(OffsetRelaxation, APatchCopiedWholeKeepsItsHeights) {
    double spacing = 0.0;
    const DatabaseLevel level = exemplarLevel("orom_rockies", &spacing);
    std::vector<PixelState> state = patch(96, 96, 150, 200, 7.0f);
    relaxOffsets(level, {0, 0, 96, 96}, spacing, kIterations, {}, state.data());
    for (const PixelState& s : state) ASSERT_NEAR(s.v, 7.0f, 1e-3f);
}

TEST(OffsetRelaxation, TheStepWhereTwoPatchesOfGentleGroundMeetCloses) {
    double spacing = 0.0;
    const DatabaseLevel level = exemplarLevel("orom_appalachians", &spacing);
    constexpr int kWidth = 96, kHeight = 64, kSeam = 48;
    // West of the seam one piece of the exemplar, east of it another (other ground, hundreds of metres
    // apart in height, and V 25 m higher): a seam the exemplar does not have.
    std::vector<PixelState> state =
        seamed(patch(kWidth, kHeight, 60, 300, 0.0f), patch(kWidth, kHeight, 340 - kSeam, 120, 25.0f), kWidth, kSeam);
    const std::vector<PixelState> before = state;
    // How far the step across the seam is from the exemplar's own step there (the target of the
    // pair, as the relaxation sees it), averaged along the seam.
    auto seamMismatch = [&](const std::vector<PixelState>& s) {
        double sum = 0.0;
        for (int y = 0; y < kHeight; ++y) {
            const PixelState& p = s[static_cast<size_t>(y) * kWidth + kSeam - 1];
            const PixelState& q = s[static_cast<size_t>(y) * kWidth + kSeam];
            const float own_p = level.height_m[static_cast<size_t>(p.y) * level.width + p.x + 1] -
                                level.height_m[static_cast<size_t>(p.y) * level.width + p.x];
            const float own_q = level.height_m[static_cast<size_t>(q.y) * level.width + q.x] -
                                level.height_m[static_cast<size_t>(q.y) * level.width + q.x - 1];
            sum += std::abs(heightOf(level, q) - heightOf(level, p) - 0.5f * (own_p + own_q));
        }
        return sum / kHeight;
    };
    relaxOffsets(level, {0, 0, kWidth, kHeight}, spacing, kIterations, {}, state.data());
    const double mismatch_before = seamMismatch(before), mismatch_after = seamMismatch(state);
    std::printf("seam mismatch %.2f m -> %.2f m\n", mismatch_before, mismatch_after);
    EXPECT_GT(mismatch_before, 15.0);
    EXPECT_LT(mismatch_after, 0.25 * mismatch_before);
    // Beyond the reach of the iterations nothing moved (a patch's interior keeps its heights).
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            if (std::abs(x - kSeam) <= kIterations + 1) continue;
            const size_t i = static_cast<size_t>(y) * kWidth + x;
            ASSERT_NEAR(state[i].v, before[i].v, 1e-3f) << x << "," << y;
        }
}

TEST(OffsetRelaxation, FixedPixelsKeepTheirOffsetsBitForBit) {
    double spacing = 0.0;
    const DatabaseLevel level = exemplarLevel("orom_appalachians", &spacing);
    constexpr int kSide = 64;
    // A seam through the middle, so pixels move.
    std::vector<PixelState> state = seamed(patch(kSide, kSide, 60, 300, 0.0f), patch(kSide, kSide, 300, 60, 30.0f), kSide, kSide / 2);
    const size_t constrained = 20 * kSide + 31, ceiling = 40 * kSide + 32, frozen = 10 * kSide + 33;
    std::vector<float> blend(4 * state.size(), 0.0f);
    blend[4 * constrained] = 1.0f;
    state[ceiling].ceiling = heightOf(level, state[ceiling]) + 1.0f;
    std::vector<uint8_t> coherence(state.size(), static_cast<uint8_t>(Coherence::Free));
    coherence[frozen] = static_cast<uint8_t>(Coherence::Frozen);
    PassHistory relaxed;
    relaxed.index.assign(state.size(), kNoPrevious);
    relaxed.v.assign(state.size(), 0.0f);
    relaxed.index[frozen] = static_cast<uint32_t>(std::lround(state[frozen].y) * level.width + std::lround(state[frozen].x));
    relaxed.v[frozen] = 12.5f;
    const std::vector<PixelState> before = state;
    relaxOffsets(level, {0, 0, kSide, kSide}, spacing, kIterations, {&coherence, &relaxed, &blend}, state.data());
    EXPECT_EQ(state[constrained].v, before[constrained].v);
    EXPECT_EQ(state[ceiling].v, before[ceiling].v);
    EXPECT_EQ(state[frozen].v, 12.5f);
    // Their neighbours did move: the seam is there.
    EXPECT_NE(state[constrained + 1].v, before[constrained + 1].v);
}

TEST(OffsetRelaxation, APixelDependsOnlyOnTheStateWithinTheReach) {
    double spacing = 0.0;
    const DatabaseLevel level = exemplarLevel("orom_rockies", &spacing);
    // 330 rows: several bands of the relaxation's split. Sources jump every 37 pixels, so most pixels
    // take part in a seam.
    constexpr int kWidth = 40, kHeight = 330;
    std::vector<PixelState> state(static_cast<size_t>(kWidth) * kHeight);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            PixelState& s = state[static_cast<size_t>(y) * kWidth + x];
            const int piece = (x / 37) + 3 * (y / 37);
            s.x = static_cast<float>(20 + (piece * 53) % 500 + x % 37);
            s.y = static_cast<float>(20 + (piece * 97) % 500 + y % 37);
            s.v = static_cast<float>(piece % 5) * 4.0f, s.ceiling = INFINITY;
        }
    std::vector<PixelState> whole = state;
    relaxOffsets(level, {0, 0, kWidth, kHeight}, spacing, kIterations, {}, whole.data());
    constexpr int kTop = 61, kRows = 200;
    std::vector<PixelState> part(state.begin() + static_cast<ptrdiff_t>(kTop) * kWidth,
                                 state.begin() + static_cast<ptrdiff_t>(kTop + kRows) * kWidth);
    relaxOffsets(level, {0, kTop, kWidth, kRows}, spacing, kIterations, {}, part.data());
    int moved = 0;
    for (int y = kIterations; y < kRows - kIterations; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t i = static_cast<size_t>(y) * kWidth + x, j = static_cast<size_t>(kTop + y) * kWidth + x;
            ASSERT_EQ(part[i].v, whole[j].v) << x << "," << y;
            moved += whole[j].v != state[j].v;
        }
    EXPECT_GT(moved, kWidth * 20);
}

}  // namespace
}  // namespace terrasynth::synth
