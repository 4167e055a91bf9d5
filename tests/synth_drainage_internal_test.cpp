// Issue 17: breaching keeps the exemplars' own basins, no deeper than they are there
// (drainage_breach.h). A hand-made atlas level holds two 12x12 exemplars: a bowl (height = distance
// from its centre, so its centre lies 5 m under the lowest point of its rim) and a level plain.
// Syntheses are copies of them with height offsets V, so the expected depressions are known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "synth/drainage_breach.h"
#include "terrasynth/terrain_stats.h"

namespace terrasynth::synth {
namespace {

constexpr int kSide = 12;      // each exemplar
constexpr int kCentre = 6;     // the bowl's lowest pixel
constexpr float kBowlDepth = 5.0f;  // its rim is lowest at (11, 6) and (6, 11): 5 m from the centre

DatabaseLevel bowlAndPlain() {
    DatabaseLevel l;
    l.width = 2 * kSide;
    l.height = kSide;
    l.height_m.assign(l.pixelCount(), 0.0f);
    l.type.assign(l.pixelCount(), 0);
    l.exemplar.assign(l.pixelCount(), 0);
    l.closed.assign(l.pixelCount(), 0);
    l.rects = {{0, 0, kSide, kSide}, {kSide, 0, kSide, kSide}};
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
            l.height_m[static_cast<size_t>(y) * l.width + x] = std::hypot(static_cast<float>(x - kCentre), static_cast<float>(y - kCentre));
            l.exemplar[static_cast<size_t>(y) * l.width + kSide + x] = 1;
        }
    return l;
}

// A 24x12 synthesis: the bowl copied as it is on the left, the plain 20 m lower on the right, so
// the bowl's water has somewhere to go within the breach radius.
std::vector<PixelState> bowlBesideLowPlain() {
    std::vector<PixelState> state(static_cast<size_t>(2 * kSide) * kSide);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < 2 * kSide; ++x) {
            PixelState& s = state[static_cast<size_t>(y) * 2 * kSide + x];
            s.x = static_cast<float>(x), s.y = static_cast<float>(y);
            s.v = x < kSide ? 0.0f : -20.0f;
        }
    return state;
}

Heightfield heights(const DatabaseLevel& db, const std::vector<PixelState>& state) {
    Heightfield f(2 * kSide, kSide, 1.0);
    for (size_t i = 0; i < state.size(); ++i) f.heights[i] = heightBilinear(db, state[i].x, state[i].y) + state[i].v;
    return f;
}

// How deep the water would stand on the bowl's centre (the field's right edge drains).
float depthAtCentre(const Heightfield& f) {
    const Heightfield filled = fillDepressions(f, false);
    return filled.at(kCentre, kCentre) - f.at(kCentre, kCentre);
}

BreachCounts breach(const DatabaseLevel& db, const std::vector<float>& closed, std::vector<PixelState>& state) {
    DrainageInputs in;
    in.closed_depth = &closed;
    return breachPits(db, {0, 0, 2 * kSide, kSide}, 8, in, state);
}

TEST(Drainage, ClosedDepthsAreTheExemplarsOwnFillDepths) {
    const DatabaseLevel db = bowlAndPlain();
    const std::vector<float> depth = ownFillDepths(db);
    ASSERT_EQ(depth.size(), db.pixelCount());
    EXPECT_FLOAT_EQ(depth[kCentre * db.width + kCentre], kBowlDepth);
    EXPECT_FLOAT_EQ(depth[kCentre * db.width + 0], 0.0f) << "the bowl's edge drains";
    for (int y = 0; y < kSide; ++y)
        for (int x = kSide; x < 2 * kSide; ++x) EXPECT_EQ(depth[static_cast<size_t>(y) * db.width + x], 0.0f) << x << "," << y;
}

TEST(Drainage, CoarseLevelsTakeTheDepthsOfTheFullResolutionExemplar) {
    // A coarse level's own basins may be artefacts of averaging (a gorge closed by its walls), so a
    // coarse pixel counts as closed as deep as its level-0 block is on average.
    ExemplarDatabase db;
    db.levels.push_back(bowlAndPlain());
    DatabaseLevel coarse;
    coarse.width = kSide, coarse.height = kSide / 2;
    coarse.rects = {{0, 0, kSide / 2, kSide / 2}, {kSide / 2, 0, kSide / 2, kSide / 2}};
    coarse.height_m.assign(coarse.pixelCount(), 10.0f);
    coarse.height_m[3 * coarse.width + kSide / 2 + 3] = 0.0f;  // a pit in the coarse plain only
    db.levels.push_back(coarse);
    ASSERT_GT(ownFillDepths(db.levels[1])[3 * coarse.width + kSide / 2 + 3], 0.0f);
    const std::vector<float> level0 = ownFillDepths(db.levels[0]);
    const std::vector<float> depth = closedDepths(db, 1, level0);
    EXPECT_EQ(depth[3 * coarse.width + kSide / 2 + 3], 0.0f) << "the plain drains at full resolution";
    const auto at0 = [&](int x, int y) { return level0[static_cast<size_t>(y) * db.levels[0].width + x]; };
    EXPECT_FLOAT_EQ(depth[3 * coarse.width + 3], (at0(6, 6) + at0(7, 6) + at0(6, 7) + at0(7, 7)) / 4.0f);
    EXPECT_GT(depth[3 * coarse.width + 3], 0.0f);
    EXPECT_EQ(closedDepths(db, 0, level0), level0);
}

TEST(Drainage, ACopiedBasinNoDeeperThanItsSourceIsKept) {
    const DatabaseLevel db = bowlAndPlain();
    const std::vector<float> closed = ownFillDepths(db);
    std::vector<PixelState> state = bowlBesideLowPlain();
    const std::vector<PixelState> before = state;
    ASSERT_NEAR(depthAtCentre(heights(db, state)), kBowlDepth, 1e-5f);
    const BreachCounts counts = breach(db, closed, state);
    EXPECT_GE(counts.kept, 1u);
    EXPECT_EQ(counts.breached, 0u);
    for (size_t i = 0; i < state.size(); ++i) ASSERT_EQ(state[i].v, before[i].v) << "pixel " << i;
}

TEST(Drainage, ACopiedBasinDeeperThanItsSourceIsCarvedToTheSourcesDepth) {
    const DatabaseLevel db = bowlAndPlain();
    const std::vector<float> closed = ownFillDepths(db);
    std::vector<PixelState> state = bowlBesideLowPlain();
    for (size_t i = 0; i < state.size(); ++i)  // the rim raised by 3 m: an 8 m deep basin
        if (state[i].x < kSide && std::hypot(state[i].x - kCentre, state[i].y - kCentre) >= 3.5f) state[i].v = 3.0f;
    ASSERT_NEAR(depthAtCentre(heights(db, state)), kBowlDepth + 3.0f, 1e-5f);
    EXPECT_GE(breach(db, closed, state).breached, 1u);
    EXPECT_NEAR(depthAtCentre(heights(db, state)), kBowlDepth, 1e-3f) << "the basin spills where its source did";
}

TEST(Drainage, ABasinCopiedFromDrainingTerrainIsDrained) {
    const DatabaseLevel db = bowlAndPlain();
    const std::vector<float> closed = ownFillDepths(db);
    std::vector<PixelState> state = bowlBesideLowPlain();
    for (size_t i = 0; i < state.size(); ++i) {  // the left half now copies the plain, with a 4 m pit
        const int x = static_cast<int>(i) % (2 * kSide), y = static_cast<int>(i) / (2 * kSide);
        if (x >= kSide) continue;
        state[i].x = static_cast<float>(kSide + x);
        state[i].v = (x == kCentre && y == kCentre) ? -4.0f : 0.0f;
    }
    ASSERT_NEAR(depthAtCentre(heights(db, state)), 4.0f, 1e-5f);
    EXPECT_GE(breach(db, closed, state).breached, 1u);
    EXPECT_EQ(depthAtCentre(heights(db, state)), 0.0f);
}

}  // namespace
}  // namespace terrasynth::synth
