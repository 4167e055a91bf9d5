// The offset h a correction gives a pixel (eq. 7): the mean of its four diagonal neighbourhoods'
// mode-0 gaps at the coarser levels, their median at the finest (kMedianOffsetLevels,
// reference_kernels.h), so a pixel whose neighbours come from two patches follows the three that
// agree. The kernel `correct` equals the reference (SynthesisDifferential.* in cl_synthesis_test).
// The level exemplar is flat (every appearance 0), so every candidate fits equally and the pixel's
// height is its offset alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "synth/reference_kernels.h"

namespace terrasynth::synth {
namespace {

constexpr int kSide = 9;                 // region pixels
constexpr int kCentre = 4;               // the pixel under test (parity 0, 0)
constexpr float kOutlierOffset = 9.0f;   // metres, on the south-east diagonal only

DatabaseLevel flatLevel() {
    DatabaseLevel l;
    l.width = l.height = 16;
    l.height_m.assign(l.pixelCount(), 0.0f);
    l.appearance.assign(l.pixelCount() * 4, 0);
    l.similar.resize(l.pixelCount());
    for (size_t i = 0; i < l.pixelCount(); ++i) l.similar[i] = static_cast<uint32_t>(i);
    l.type.assign(l.pixelCount(), 0);
    l.exemplar.assign(l.pixelCount(), 0);
    l.closed.assign(l.pixelCount(), 0);
    l.rects = {{0, 0, 16, 16}};
    return l;
}

// V of the centre pixel after one correction subpass of its parity class at `level`, every other
// pixel at V = 0 but its south-east diagonal neighbour.
float centreOffsetAfterCorrection(int level) {
    const DatabaseLevel db = flatLevel();
    std::vector<PixelState> state(static_cast<size_t>(kSide) * kSide);
    for (PixelState& s : state) s.x = s.y = 8.0f, s.v = 0.0f, s.ceiling = INFINITY;
    state[static_cast<size_t>(kCentre + 1) * kSide + kCentre + 1].v = kOutlierOffset;
    CorrectionContext context;
    context.level = level;
    referenceCorrect(db, {0, 0, kSide, kSide}, 0, 0, 2, context, state);
    return state[static_cast<size_t>(kCentre) * kSide + kCentre].v;
}

TEST(Correction, TheFinestLevelsFollowTheThreeDiagonalsThatAgree) {
    // N_S of the south-east diagonal averages three pixels (eq. 6), one of them the outlier: its gap
    // is a third of the outlier's offset, the other three gaps 0.
    for (int level = 0; level < kMedianOffsetLevels; ++level)
        EXPECT_EQ(centreOffsetAfterCorrection(level), 0.0f) << "level " << level;
}

TEST(Correction, CoarserLevelsTakeTheMeanGapAsThePaperDoes) {
    const float mean_gap = kOutlierOffset / 3.0f / 4.0f;
    for (int level = kMedianOffsetLevels; level < kMedianOffsetLevels + 3; ++level)
        EXPECT_NEAR(centreOffsetAfterCorrection(level), mean_gap, 1e-5f) << "level " << level;
}

}  // namespace
}  // namespace terrasynth::synth
