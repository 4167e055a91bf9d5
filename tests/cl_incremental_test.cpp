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
    // The update lifts the point (liftPointConstraints) so its site lands on the asked height.
    const HeightRange relief = heightRange(after);
    std::printf("site %.2f m from the target (relief %.0f m)\n", std::fabs(after.at(250, 260) - target), relief.max - relief.min);
    EXPECT_LT(std::fabs(after.at(250, 260) - target), 0.02f * (relief.max - relief.min));

    // A second edit moves the constraint back down: the terrain follows, again only locally.
    auto lower = std::make_shared<SynthesisConstraints>();
    lower->points.push_back({250.0, 260.0, before.at(250, 260) - 300.0f, 0.0f, 0.0f, 64.0f});
    const Heightfield first_edit = after;
    ASSERT_TRUE(terrain->update(lower, changed));
    EXPECT_LT(terrain->heights().at(250, 260), first_edit.at(250, 260));
    EXPECT_EQ(terrain->heights().at(5, 5), before.at(5, 5));
}

TEST(Incremental, PasteFromAnExemplarIsExactFrozenAndBlends) {
    auto s = Synthesizer::create(test::defaultDatabase());
    ASSERT_TRUE(s) << s.message();
    const PixelWindow extent{0, 0, 384, 384};
    auto terrain = IncrementalTerrain::create(*s.value(), extent, SynthesisParams{});
    ASSERT_TRUE(terrain) << terrain.message();
    const Heightfield before = terrain->heights();
    // A 60x50 rectangle of the Himalaya exemplar (index 2) pasted at (150, 160), raised by 120 m.
    const ExemplarDatabase& db = *test::defaultDatabase();
    const int himalaya = 2;
    ASSERT_EQ(db.exemplars[himalaya].name, "orom_himalaya-everest");
    IncrementalTerrain::Paste paste;
    paste.exemplar = himalaya;
    paste.source = {{300, 300}, {360, 300}, {360, 350}, {300, 350}};
    paste.dx = -150, paste.dy = -140;
    paste.height_offset_m = 120.0f;
    ASSERT_TRUE(terrain->paste(paste));
    const Heightfield& after = terrain->heights();
    const DatabaseLevel& l0 = db.levels[0];
    const AtlasRect& r = l0.rects[himalaya];
    int checked = 0;
    for (int y = 165; y < 205; ++y)
        for (int x = 155; x < 205; ++x) {
            const float exemplar = l0.height_m[static_cast<size_t>(r.y + y + 140) * l0.width + r.x + x + 150];
            ASSERT_NEAR(after.at(x, y), exemplar + 120.0f, 1e-3f) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 1000);
    // Far away nothing moved; the ring around the paste was re-synthesized to blend.
    EXPECT_EQ(after.at(5, 370), before.at(5, 370));
    // Pasted pixels stay bit-identical through a later edit next to them.
    const Heightfield pasted = after;
    auto c = std::make_shared<SynthesisConstraints>();
    c->points.push_back({230.0, 180.0, pasted.at(230, 180) + 400.0f, 0.0f, 0.0f, 48.0f});
    ASSERT_TRUE(terrain->update(c, {230 - 48, 180 - 48, 97, 97}));
    for (int y = 165; y < 205; ++y)
        for (int x = 155; x < 205; ++x) ASSERT_EQ(terrain->heights().at(x, y), pasted.at(x, y));
}
