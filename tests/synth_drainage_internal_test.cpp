// Issue 17: a pit with no lower pixel within the breach radius (a regional low of the coarse
// levels) is carved to the cheapest pixel on its search window's edge, which ends below the pit
// (DrainageInputs::carve_to_edge), and a protected pixel is never lowered (drainage_breach.h).
// The synthesis is a cone of height offsets V over a level exemplar, so its apex-down centre is the
// lowest pixel of the whole region.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "synth/drainage_breach.h"

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

BreachCounts breach(std::vector<PixelState>& state, bool to_edge, const std::vector<float>* blend = nullptr) {
    const DatabaseLevel db = levelExemplar();
    DrainageInputs in;
    in.carve_to_edge = to_edge;
    in.blend = blend;
    return breachPits(db, {0, 0, kSide, kSide}, kRadius, in, state);
}

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
    EXPECT_NEAR(minOnWindowEdge(state), pit - kEdgeDrop, 1e-5f) << "the channel ends below the pit";
    // The channel leaves westwards (the cheaper side) and descends from the pit to its end.
    const float west = state[static_cast<size_t>(kCentre) * kSide + kCentre - kRadius].v;
    EXPECT_LT(west, pit);
    for (int x = kCentre - kRadius + 1; x < kCentre; ++x)
        EXPECT_LE(state[static_cast<size_t>(kCentre) * kSide + x - 1].v, state[static_cast<size_t>(kCentre) * kSide + x].v) << x;
    for (int x = kCentre + 1; x < kSide; ++x)  // the dearer side is untouched
        EXPECT_GT(state[static_cast<size_t>(kCentre) * kSide + x].v, 0.0f) << x;
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

}  // namespace
}  // namespace terrasynth::synth
