// Incremental re-synthesis after a local edit (issue: only the region that can change is redone).
#include <gtest/gtest.h>

#include <cmath>

#include "terrasynth/incremental.h"
#include "test_support.h"

using namespace terrasynth;

TEST(Incremental, LocalEditMatchesFullResynthesisAndLeavesTheRestUntouched) {
    auto s = Synthesizer::create(test::defaultDatabase());
    ASSERT_TRUE(s) << s.message();
    const PixelWindow extent{0, 0, 512, 512};
    SynthesisParams params;
    params.seed = 12;
    auto terrain = IncrementalTerrain::create(*s.value(), extent, params);
    ASSERT_TRUE(terrain) << terrain.message();
    const Heightfield before = terrain->heights();

    auto constraints = std::make_shared<SynthesisConstraints>();
    const float target = before.at(250, 260) + 500.0f;
    constraints->points.push_back({250.0, 260.0, target, 0.0f, 0.0f, 64.0f});
    const PixelWindow changed{250 - 64, 260 - 64, 129, 129};
    ASSERT_TRUE(terrain->update(constraints, changed));
    const Heightfield& after = terrain->heights();
    const PixelWindow w = terrain->lastWindow();
    std::printf("re-synthesized %dx%d of 512x512\n", w.width, w.height);
    EXPECT_LT(static_cast<double>(w.width) * w.height, 0.4 * 512 * 512);

    size_t outside_changed = 0;
    for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 512; ++x) {
            const bool in_window = x >= w.x && y >= w.y && x < w.x + w.width && y < w.y + w.height;
            if (!in_window) outside_changed += after.at(x, y) != before.at(x, y);
        }
    EXPECT_EQ(outside_changed, 0u);
    EXPECT_LT(std::fabs(after.at(250, 260) - target), 0.5f * std::fabs(before.at(250, 260) - target));

    // A second edit moves the constraint back down: the terrain follows, again only locally.
    auto lower = std::make_shared<SynthesisConstraints>();
    lower->points.push_back({250.0, 260.0, before.at(250, 260) - 300.0f, 0.0f, 0.0f, 64.0f});
    const Heightfield first_edit = after;
    ASSERT_TRUE(terrain->update(lower, changed));
    EXPECT_LT(terrain->heights().at(250, 260), first_edit.at(250, 260));
    EXPECT_EQ(terrain->heights().at(5, 5), before.at(5, 5));
}
