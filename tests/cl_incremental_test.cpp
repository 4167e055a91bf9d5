// Incremental re-synthesis after a local edit (issue: only the region that can change is redone).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "terrasynth/curve_course.h"
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
    // Exact off the paste's rim (kPasteBlendPx), which blends with the surroundings.
    for (int y = 166; y < 205; ++y)
        for (int x = 156; x < 205; ++x) {
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
    for (int y = 166; y < 205; ++y)
        for (int x = 156; x < 205; ++x) ASSERT_EQ(terrain->heights().at(x, y), pasted.at(x, y));
}

TEST(Incremental, DraggedCurveWidgetKeepsTheCourseOnItsHeights) {
    // As a project edits (hold_point_heights): the first edit searches the curve's lift profile, the
    // drags after it keep it (same course) and stay local.
    auto s = Synthesizer::create(test::defaultDatabase());
    ASSERT_TRUE(s) << s.message();
    const PixelWindow extent{0, 0, 512, 512};
    SynthesisParams params;
    params.seed = 5;
    params.hold_on_free_levels = true;
    auto terrain = IncrementalTerrain::create(*s.value(), extent, params);
    ASSERT_TRUE(terrain) << terrain.message();
    const float base = terrain->heights().at(250, 250);
    auto valley = [&](float raise) {
        auto c = std::make_shared<SynthesisConstraints>();
        CurveConstraint curve;
        curve.course = {{150.0, 280.0}, {250.0, 240.0}, {360.0, 270.0}};
        for (double t : {0.0, 0.5, 1.0}) {
            CurveWidget w;
            w.t = t;
            w.height_m = base - 200.0f + (t == 0.5 ? raise : 0.0f);
            w.left_gradient = 0.2f, w.right_gradient = 0.25f;
            w.left_reach_px = 40.0f, w.right_reach_px = 50.0f;
            curve.widgets.push_back(w);
        }
        c->curves.push_back(curve);
        return c;
    };
    for (float raise : {0.0f, 120.0f, 240.0f, 60.0f}) {
        const Heightfield before = terrain->heights();
        ASSERT_TRUE(terrain->applyEdit(valley(raise)));
        const Heightfield& after = terrain->heights();
        const CurveHold hold = measureCurveHold(after, 0, 0, terrain->params().constraints->curves, 0,
                                                test::defaultDatabase()->meters_per_pixel);
        std::vector<float> miss = hold.height_error_m;
        for (float& m : miss) m = std::fabs(m);
        std::sort(miss.begin(), miss.end());
        const HeightRange r = heightRange(after);
        const float median = miss[miss.size() / 2] / (r.max - r.min), p95 = miss[miss.size() * 95 / 100] / (r.max - r.min);
        std::printf("middle widget raised %.0f m: course %.2f%% of the relief from its heights at the median, %.2f%% at the "
                    "95th percentile\n",
                    raise, 100 * median, 100 * p95);
        EXPECT_LE(median, 0.01f);
        EXPECT_LE(p95, 0.03f);
        ASSERT_FALSE(terrain->params().constraints->curves[0].lift_m.empty());
        const PixelWindow w = terrain->lastWindow();
        for (int y = 0; y < 512; ++y)
            for (int x = 0; x < 512; ++x)
                if (!w.contains(x, y)) {
                    ASSERT_EQ(after.at(x, y), before.at(x, y)) << x << "," << y;
                }
    }
}
