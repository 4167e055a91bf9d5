// Issue 17: a pit with no lower pixel within the breach radius (a regional low of the coarse
// levels) is carved to the cheapest pixel on its search window's edge, which ends below the pit
// (DrainageInputs::carve_to_edge), and a protected pixel is never lowered (drainage_breach.h).
// A path goes to a pixel depth_margin below the pit when one is within reach, else to the first
// lower pixel the search meets (the search stops there early when the window's minimum says the
// margin is out of reach). Diagonal steps carve a side cell too, and the level ground a pit lies in
// is not carved.
// The synthesis is a cone of height offsets V over a level exemplar, so its apex-down centre is the
// lowest pixel of the whole region.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "synth/drainage_breach.h"
#include "synth/level_ground.h"

namespace terrasynth::synth {
namespace {

constexpr int kSide = 41;   // region pixels
constexpr int kCentre = 20;
constexpr int kRadius = 8;

DatabaseLevel levelExemplar() {
    DatabaseLevel l;
    l.width = l.height = 16;
    l.height_m.assign(l.pixelCount(), 0.0f);
    l.type.assign(l.pixelCount(), 0);
    l.exemplar.assign(l.pixelCount(), 0);
    l.closed.assign(l.pixelCount(), 0);
    l.rects = {{0, 0, 16, 16}};
    return l;
}

// V rises with the distance from the centre, a little faster away from the western half-row, so
// the cheapest way out of the basin runs due west.
std::vector<PixelState> cone() {
    std::vector<PixelState> state(static_cast<size_t>(kSide) * kSide);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
            PixelState& s = state[static_cast<size_t>(y) * kSide + x];
            s.x = s.y = 8.0f;
            s.v = std::hypot(static_cast<float>(x - kCentre), static_cast<float>(y - kCentre)) +
                  0.5f * static_cast<float>(std::max(0, x - kCentre) + std::abs(y - kCentre));
        }
    return state;
}

float minOnWindowEdge(const std::vector<PixelState>& state) {
    float lowest = INFINITY;
    for (int y = kCentre - kRadius; y <= kCentre + kRadius; ++y)
        for (int x = kCentre - kRadius; x <= kCentre + kRadius; ++x)
            if (std::max(std::abs(x - kCentre), std::abs(y - kCentre)) == kRadius)
                lowest = std::min(lowest, state[static_cast<size_t>(y) * kSide + x].v);
    return lowest;
}

BreachCounts breach(std::vector<PixelState>& state, bool to_edge, const std::vector<float>* blend = nullptr,
                    float depth_margin = 0.0f, const std::vector<uint8_t>* basin_exemplars = nullptr,
                    float level_tolerance = -1.0f) {
    const DatabaseLevel db = levelExemplar();
    DrainageInputs in;
    in.carve_to_edge = to_edge;
    in.blend = blend;
    in.depth_margin = depth_margin;
    in.basin_exemplars = basin_exemplars;
    // The level exemplar is level ground everywhere but on its outer ring (levelGroundFlags).
    const std::vector<uint8_t> level_ground = levelGroundFlags(db, level_tolerance);
    if (level_tolerance >= 0.0f) in.level_ground = &level_ground, in.level_tolerance = level_tolerance;
    return breachPits(db, {0, 0, kSide, kSide}, kRadius, in, state.data());
}

// A plain of V = `height` over the flat level exemplar, and V at region pixel (x, y).
std::vector<PixelState> plain(float height) {
    std::vector<PixelState> state(static_cast<size_t>(kSide) * kSide);
    for (PixelState& s : state) s.x = s.y = 8.0f, s.v = height;
    return state;
}
float& vAt(std::vector<PixelState>& state, int x, int y) { return state[static_cast<size_t>(y) * kSide + x].v; }

TEST(Drainage, ARegionalLowStaysWithoutCarvingToTheEdge) {
    std::vector<PixelState> state = cone();
    const std::vector<PixelState> before = state;
    const BreachCounts counts = breach(state, false);
    EXPECT_EQ(counts.pits, 1u);
    EXPECT_EQ(counts.breached, 0u);
    for (size_t i = 0; i < state.size(); ++i) ASSERT_EQ(state[i].v, before[i].v) << "pixel " << i;
}

TEST(Drainage, ARegionalLowIsCarvedDownToTheCheapestEdgeOfItsWindow) {
    std::vector<PixelState> state = cone();
    const BreachCounts counts = breach(state, true);
    EXPECT_EQ(counts.breached, 1u);
    const float pit = state[static_cast<size_t>(kCentre) * kSide + kCentre].v;
    EXPECT_EQ(pit, 0.0f) << "the pit itself is not lowered";
    EXPECT_NEAR(minOnWindowEdge(state), pit - kBreachProfileDepth * kEdgeDrop, 1e-5f) << "the channel ends below the pit";
    // The channel leaves westwards (the cheaper side) and descends from the pit to its end.
    const float west = state[static_cast<size_t>(kCentre) * kSide + kCentre - kRadius].v;
    EXPECT_LT(west, pit);
    for (int x = kCentre - kRadius + 1; x < kCentre; ++x)
        EXPECT_LE(state[static_cast<size_t>(kCentre) * kSide + x - 1].v, state[static_cast<size_t>(kCentre) * kSide + x].v) << x;
    for (int x = kCentre + 1; x < kSide; ++x)  // the dearer side is untouched
        EXPECT_GT(state[static_cast<size_t>(kCentre) * kSide + x].v, 0.0f) << x;
}

TEST(Drainage, ARegionalLowOfAnExemplarWithRealBasinsIsKept) {
    // Lava plains and salars hold closed basins the exemplar itself has: their regional lows stay.
    const std::vector<uint8_t> exemplar0_has_basins = {1};
    std::vector<PixelState> state = cone();
    const std::vector<PixelState> before = state;
    EXPECT_EQ(breach(state, true, nullptr, 0.0f, &exemplar0_has_basins).breached, 0u);
    for (size_t i = 0; i < state.size(); ++i) ASSERT_EQ(state[i].v, before[i].v) << "pixel " << i;
    // Another exemplar's basins change nothing here: the low is carved to the edge as before.
    const std::vector<uint8_t> only_exemplar1 = {0, 1};
    EXPECT_EQ(breach(state, true, nullptr, 0.0f, &only_exemplar1).breached, 1u);
    EXPECT_LT(minOnWindowEdge(state), 0.0f);
}

TEST(Drainage, APitOfAnExemplarWithRealBasinsStillDrainsToALowerPixelInReach) {
    // Only regional lows are kept: a pit with a lower pixel within the radius drains as always.
    const std::vector<uint8_t> exemplar0_has_basins = {1};
    std::vector<PixelState> state = plain(10.0f);
    vAt(state, kCentre, kCentre) = 0.0f;
    vAt(state, kCentre - 5, kCentre) = -3.0f;
    EXPECT_EQ(breach(state, true, nullptr, 0.0f, &exemplar0_has_basins).breached, 1u);
    for (int x = kCentre - 4; x < kCentre; ++x) EXPECT_LT(vAt(state, x, kCentre), 10.0f) << x;
}

TEST(Drainage, ExemplarsWithRealBasinsAreThoseWithManyClosedPixels) {
    // Two exemplars side by side at level 0: the first with 1 closed pixel in 64 (1.6%), the second
    // with 4 in 64 (6.3%); kRealBasinShare = 4% lies between.
    ExemplarDatabase db;
    db.exemplars.resize(2);
    DatabaseLevel l;
    l.width = 16, l.height = 8;
    l.exemplar.assign(l.pixelCount(), 0);
    l.closed.assign(l.pixelCount(), 0);
    for (int y = 0; y < 8; ++y)
        for (int x = 8; x < 16; ++x) l.exemplar[static_cast<size_t>(y) * 16 + x] = 1;
    l.closed[0] = 1;
    for (int i = 0; i < 4; ++i) l.closed[static_cast<size_t>(i) * 16 + 9] = 1;
    db.levels.push_back(l);
    EXPECT_EQ(exemplarsWithRealBasins(db), (std::vector<uint8_t>{0, 1}));
}

TEST(Drainage, AProtectedPixelOnTheEdgeIsNeverLowered) {
    // Point or curve constraints (blend > 0) on the whole window edge: no path may end there.
    std::vector<float> blend(4 * static_cast<size_t>(kSide) * kSide, 0.0f);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            if (std::max(std::abs(x - kCentre), std::abs(y - kCentre)) == kRadius) blend[4 * (static_cast<size_t>(y) * kSide + x)] = 1.0f;
    std::vector<PixelState> state = cone();
    const std::vector<PixelState> before = state;
    breach(state, true, &blend);
    for (size_t i = 0; i < state.size(); ++i) ASSERT_EQ(state[i].v, before[i].v) << "pixel " << i;
}

// A plain at 10 m near the region's north edge (so the search windows are clipped by it), with a pit
// at 0 m, a shallow hollow 4 pixels east (-0.5 m) and, optionally, a deep one 7 pixels west (-5 m).
constexpr int kRow = 3, kPit = 20, kShallow = 24, kDeep = 13;
std::vector<float> rowAfterBreach(bool deep, float depth_margin) {
    std::vector<PixelState> state = plain(10.0f);
    vAt(state, kPit, kRow) = 0.0f;
    vAt(state, kShallow, kRow) = -0.5f;
    if (deep) vAt(state, kDeep, kRow) = -5.0f;
    breach(state, false, nullptr, depth_margin);
    std::vector<float> row(kSide);
    for (int x = 0; x < kSide; ++x) row[x] = vAt(state, x, kRow);
    return row;
}

TEST(Drainage, APitDrainsToAPixelTheDepthMarginBelowWhenOneIsInReach) {
    const std::vector<float> row = rowAfterBreach(true, 2.0f);
    // The shallow hollow is nearer and cheaper, but only the deep one is 2 m below the pit. The
    // profile descends kBreachProfileDepth of the way to it, so the hollow itself stays.
    for (int x = kDeep + 1; x < kPit; ++x)
        EXPECT_NEAR(row[x], -5.0f * kBreachProfileDepth * static_cast<float>(kPit - x) / (kPit - kDeep), 1e-5f) << x;
    EXPECT_EQ(row[kDeep], -5.0f);
    for (int x = kPit + 1; x < kShallow; ++x) EXPECT_EQ(row[x], 10.0f) << x;
}

TEST(Drainage, APitOutOfReachOfTheMarginDrainsToTheFirstLowerPixel) {
    for (float margin : {2.0f, 0.0f}) {
        // Without the deep hollow the margin is out of reach (the search stops at the first lower
        // pixel); with margin 0 the first lower pixel is the target anyway.
        const std::vector<float> row = rowAfterBreach(margin == 0.0f, margin);
        for (int x = kPit + 1; x < kShallow; ++x)
            EXPECT_NEAR(row[x], -0.5f * kBreachProfileDepth * static_cast<float>(x - kPit) / (kShallow - kPit), 1e-5f)
                << "margin " << margin << ", " << x;
        for (int x = kDeep + 1; x < kPit; ++x) EXPECT_EQ(row[x], 10.0f) << "margin " << margin << ", " << x;
        EXPECT_EQ(row[kShallow], -0.5f) << "the hollow has nothing lower within reach and stays";
    }
}

TEST(Drainage, APathCostsItsLengthSoDiagonalsAreNotFree) {
    // Two outlets 1 m below the pit across a plain 10 m above it: 6 pixels east (5 cells between)
    // and 5 pixels diagonally south-east (4 cells between, 7.1 pixels long). Counted per cell, the
    // diagonal was cheaper, and coarse channels ran as long 45-degree trenches; counted per unit
    // of length (cells x step length) the shorter east path wins.
    std::vector<PixelState> state = plain(10.0f);
    vAt(state, kCentre, kCentre) = 0.0f;
    vAt(state, kCentre + 6, kCentre) = -1.0f;
    vAt(state, kCentre + 5, kCentre + 5) = -1.0f;
    breach(state, false);
    for (int i = 1; i < 6; ++i) EXPECT_LT(vAt(state, kCentre + i, kCentre), 0.0f) << "east, " << i;
    for (int i = 1; i < 5; ++i) EXPECT_EQ(vAt(state, kCentre + i, kCentre + i), 10.0f) << "diagonal, " << i;
}

TEST(Drainage, ADiagonalPathIsCarvedSideBySide) {
    // The only outlet is 5 pixels diagonally south-east. Carved cells of a diagonal meet only at
    // their corners, which at 1:1 read as a dashed line of pits; each diagonal step also carves one
    // of the two cells both touch by a side, to the profile's height between them.
    std::vector<PixelState> state = plain(10.0f);
    vAt(state, kCentre, kCentre) = 0.0f;
    vAt(state, kCentre + 5, kCentre + 5) = -1.0f;
    breach(state, false);
    for (int i = 0; i < 5; ++i) {
        const float from = vAt(state, kCentre + i, kCentre + i), to = vAt(state, kCentre + i + 1, kCentre + i + 1);
        const float beside = std::min(vAt(state, kCentre + i + 1, kCentre + i), vAt(state, kCentre + i, kCentre + i + 1));
        EXPECT_LT(to, from) << "the path descends, step " << i;
        EXPECT_LT(beside, 10.0f) << "no side cell carved, step " << i;
        EXPECT_LE(beside, from) << "step " << i;
        EXPECT_GE(beside, to) << "step " << i;
    }
}

// A lake: level ground 5 pixels square at 0 m on the plain at 10 m (the exemplar is level, so
// every source is level ground at the same height), an outlet 2 m below it 3 pixels east of its
// shore, within the radius of the lake's pit (its first pixel). Returns V after the breach, with
// level ground at this tolerance, or none (negative).
constexpr int kLakeLow = 18, kLakeHigh = 22, kOutlet = 25;
std::vector<PixelState> lakeAfterBreach(float level_tolerance) {
    std::vector<PixelState> state = plain(10.0f);
    for (int y = kLakeLow; y <= kLakeHigh; ++y)
        for (int x = kLakeLow; x <= kLakeHigh; ++x) vAt(state, x, y) = 0.0f;
    vAt(state, kOutlet, kCentre) = -2.0f;
    breach(state, false, nullptr, 0.0f, nullptr, level_tolerance);
    return state;
}

TEST(Drainage, ALakeOfLevelGroundStaysLevelAndDrainsThroughItsRim) {
    std::vector<PixelState> state = lakeAfterBreach(0.5f);
    for (int y = kLakeLow; y <= kLakeHigh; ++y)
        for (int x = kLakeLow; x <= kLakeHigh; ++x) ASSERT_EQ(vAt(state, x, y), 0.0f) << "lake pixel " << x << ", " << y;
    // The rim between the shore and the outlet is cut below the lake, whichever row the path takes.
    for (int x = kLakeHigh + 1; x < kOutlet; ++x) {
        float lowest = INFINITY;
        for (int y = kLakeLow; y <= kLakeHigh; ++y) lowest = std::min(lowest, vAt(state, x, y));
        EXPECT_LT(lowest, 0.0f) << "rim column " << x;
    }
    // Carving every path cell (no tolerance) draws a trench across the lake from its pit.
    std::vector<PixelState> trenched = lakeAfterBreach(-1.0f);
    int below = 0;
    for (int y = kLakeLow; y <= kLakeHigh; ++y)
        for (int x = kLakeLow; x <= kLakeHigh; ++x) below += vAt(trenched, x, y) < 0.0f;
    EXPECT_GE(below, 3);
}

}  // namespace
}  // namespace terrasynth::synth
