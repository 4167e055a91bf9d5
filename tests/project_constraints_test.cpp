// Point constraints and type painting (paper s5.1-5.2) through a project, as a user drives them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "terrasynth/terrain.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

constexpr int kSize = 512;

std::string writeProject(const std::string& dir, const std::string& constraints, const std::string& synthesis_extra = "") {
    // The project uses the shared default database the other tests build.
    const std::string path = dir + "/world.tsyn";
    std::ofstream(path) << "{\"database\": \"" << test::defaultDatabasePath() << "\", \"size\": [" << kSize << ", "
                        << kSize << "], \"synthesis\": {\"seed\": 1" << synthesis_extra
                        << "}, \"constraints\": " << constraints << "}";
    return path;
}

SynthesisOutput synthesize(const std::string& project) {
    auto terrain = Terrain::open(project);
    EXPECT_TRUE(terrain) << terrain.message();
    auto out = terrain.value()->synthesize(terrain.value()->extent(), 0, true);
    EXPECT_TRUE(out) << out.message();
    return std::move(out.value());
}

}  // namespace

TEST(Constraints, PointConstraintPullsHeightAndSlope) {
    ASSERT_TRUE(test::defaultDatabase());
    const std::string dir = test::scratchDir("constraints_point");
    const auto free = synthesize(writeProject(dir, "{}"));
    const float before = free.heights.at(256, 256);
    const float target = before + 900.0f;
    const auto shaped = synthesize(writeProject(
        dir, "{\"points\": [{\"x\": 256, \"y\": 256, \"height_m\": " + std::to_string(target) +
                 ", \"slope_direction_deg\": 90, \"slope_angle_deg\": 15, \"radius_px\": 96}]}"));
    const float after = shaped.heights.at(256, 256);
    const HeightRange relief = heightRange(shaped.heights);
    std::printf("site: free %.1f m, target %.1f m, constrained %.1f m (terrain relief %.1f m)\n", before, target, after,
                relief.max - relief.min);
    // The error shrinks to a small part of what it was (the finest two levels are unconstrained and
    // add their own detail, paper s5.1).
    EXPECT_LT(std::fabs(after - target), 0.2f * std::fabs(before - target));
    // With the paper's defaults (off on the finest two levels) the site ends within 5% of the
    // relief; the issue asks for 2%, which needs the finest-but-one level constrained too (1.5%).
    EXPECT_LT(std::fabs(after - target), 0.05f * (relief.max - relief.min));
    // (Far from the site the terrain may still change: without coherence weights (s5.3, not yet
    // implemented) a change at a coarse level spreads through the later corrections, paper fig. 7b.)
    // The ground around the site rises towards the east, as asked: the direction of the plane fitted
    // over the inner half of the constraint's radius.
    auto planeDirection = [&](int half) {
        double east = 0.0, south = 0.0;
        for (int dy = -half; dy <= half; ++dy)
            for (int dx = -half; dx <= half; ++dx) {
                east += dx * shaped.heights.at(256 + dx, 256 + dy);
                south += dy * shaped.heights.at(256 + dx, 256 + dy);
            }
        return std::atan2(east, -south) * 180.0 / 3.14159265358979;
    };
    const double direction = planeDirection(48);
    std::printf("slope direction at the site: %.1f deg over +-48 px, %.1f deg over +-8 px (asked 90)\n", direction,
                planeDirection(8));
    EXPECT_NEAR(direction, 90.0, 15.0);
}

TEST(Constraints, ConstrainingTheFinestButOneLevelHoldsPointsWithinTwoPercent) {
    ASSERT_TRUE(test::defaultDatabase());
    const std::string dir = test::scratchDir("constraints_point_level1");
    const auto free = synthesize(writeProject(dir, "{}"));
    const float target = free.heights.at(256, 256) + 900.0f;
    const std::string point = "{\"points\": [{\"x\": 256, \"y\": 256, \"height_m\": " + std::to_string(target) +
                              ", \"slope_direction_deg\": 90, \"slope_angle_deg\": 15, \"radius_px\": 96}]}";
    const auto tight = synthesize(writeProject(dir, point, ", \"first_constrained_level\": 1"));
    const HeightRange relief = heightRange(tight.heights);
    const float error = std::fabs(tight.heights.at(256, 256) - target);
    std::printf("first constrained level 1: site %.1f m from the target, %.2f%% of the relief\n", error,
                100.0f * error / (relief.max - relief.min));
    EXPECT_LT(error, 0.02f * (relief.max - relief.min));
}

TEST(Constraints, CurveConstraintRaisesARidgeAlongItsCourse) {
    ASSERT_TRUE(test::defaultDatabase());
    const std::string dir = test::scratchDir("constraints_curve");
    const auto free = synthesize(writeProject(dir, "{}"));
    // A ridge line from (100, 300) to (420, 300) at 700 m above the free terrain's mean along it,
    // falling away on both sides.
    double mean = 0.0;
    for (int x = 100; x <= 420; ++x) mean += free.heights.at(x, 300);
    mean /= 321.0;
    const float crest = static_cast<float>(mean + 700.0);
    const auto ridge = synthesize(writeProject(
        dir, "{\"curves\": [{\"course\": [[100, 300], [420, 300]], \"spline\": false, \"widgets\": [{\"t\": 0, "
             "\"height_m\": " + std::to_string(crest) + ", \"left_gradient\": -0.3, \"right_gradient\": -0.3, "
             "\"left_reach_px\": 48, \"right_reach_px\": 48}]}]}"));
    double before = 0.0, after = 0.0;
    for (int x = 140; x <= 380; ++x) {
        before += std::fabs(free.heights.at(x, 300) - crest);
        after += std::fabs(ridge.heights.at(x, 300) - crest);
    }
    std::printf("mean distance of the course from the crest height: %.1f m free, %.1f m constrained\n", before / 241,
                after / 241);
    EXPECT_LT(after, 0.3 * before);
}

TEST(Constraints, PaintedPixelsDrawFromThePaintedType) {
    ASSERT_TRUE(test::defaultDatabase());
    const std::string dir = test::scratchDir("constraints_types");
    const auto out = synthesize(writeProject(
        dir, "{\"types\": {\"strokes\": [{\"type\": \"extreme alpine\", \"radius_px\": 40, "
             "\"points\": [[60, 100], [450, 120]]}]}}"));
    const ExemplarDatabase& db = *test::defaultDatabase();
    size_t painted = 0, matching = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            // Distance to the stroke segment.
            const double ax = 60, ay = 100, bx = 450, by = 120;
            const double t = std::clamp(((x - ax) * (bx - ax) + (y - ay) * (by - ay)) /
                                            ((bx - ax) * (bx - ax) + (by - ay) * (by - ay)), 0.0, 1.0);
            if (std::hypot(x - ax - t * (bx - ax), y - ay - t * (by - ay)) > 40.0) continue;
            ++painted;
            const int e = out.source_exemplar[static_cast<size_t>(y) * kSize + x];
            matching += db.type_names[db.exemplar_type[e]] == "extreme alpine";
        }
    std::printf("%zu painted pixels, %.2f%% drawn from extreme alpine exemplars\n", painted, 100.0 * matching / painted);
    EXPECT_GE(static_cast<double>(matching) / painted, 0.95);
}

TEST(Constraints, FreezeKeepsTheSeedTerrainAndPastesLandExactly) {
    ASSERT_TRUE(test::defaultDatabase());
    const std::string dir = test::scratchDir("constraints_freeze_paste");
    const auto free = synthesize(writeProject(dir, "{}"));
    // A point constraint whose reach covers a frozen stroke, and a paste of the Rockies exemplar.
    const auto shaped = synthesize(writeProject(
        dir, "{\"points\": [{\"x\": 200, \"y\": 200, \"height_m\": " + std::to_string(free.heights.at(200, 200) + 800) +
                 ", \"radius_px\": 120}], \"freeze\": {\"strokes\": [{\"radius_px\": 12, \"points\": [[150, 150], [250, 150]]}]}, "
                 "\"pastes\": [{\"exemplar\": \"orom_rockies\", \"source\": [[100, 100], [160, 100], [160, 150], [100, 150]], "
                 "\"target\": [380, 380], \"height_offset_m\": 50}]}"));
    for (int x = 152; x <= 248; ++x) ASSERT_EQ(shaped.heights.at(x, 150), free.heights.at(x, 150)) << "frozen pixel " << x;
    EXPECT_GT(shaped.heights.at(200, 200), free.heights.at(200, 200) + 300.0f);
    const DatabaseLevel& l0 = test::defaultDatabase()->levels[0];
    const int rockies = 3;
    const AtlasRect& r = l0.rects[rockies];
    for (int y = 385; y < 425; ++y)
        for (int x = 385; x < 435; ++x)
            ASSERT_NEAR(shaped.heights.at(x, y), l0.height_m[static_cast<size_t>(r.y + y - 280) * l0.width + r.x + x - 280] + 50.0f,
                        1e-3f);
}

TEST(Constraints, MalformedEntriesNameTheField) {
    ASSERT_TRUE(test::defaultDatabase());
    const std::string dir = test::scratchDir("constraints_errors");
    auto bad_radius = Terrain::open(writeProject(dir, "{\"points\": [{\"x\": 1, \"y\": 2, \"height_m\": 5, \"radius_px\": -4}]}"));
    ASSERT_FALSE(bad_radius);
    EXPECT_NE(bad_radius.message().find("constraints.points[0].radius_px"), std::string::npos) << bad_radius.message();
    auto bad_type = Terrain::open(writeProject(dir, "{\"types\": {\"strokes\": [{\"type\": \"lava\", \"points\": [[1, 1]]}]}}"));
    ASSERT_FALSE(bad_type);
    EXPECT_NE(bad_type.message().find("unknown terrain type \"lava\""), std::string::npos) << bad_type.message();
    auto unsupported = Terrain::open(writeProject(dir, "{\"rivers\": []}"));
    ASSERT_FALSE(unsupported);
    EXPECT_NE(unsupported.message().find("constraints.rivers"), std::string::npos) << unsupported.message();
    auto bad_widget = Terrain::open(writeProject(
        dir, "{\"curves\": [{\"course\": [[0, 0], [50, 10]], \"widgets\": [{\"t\": 2, \"height_m\": 10}]}]}"));
    ASSERT_FALSE(bad_widget);
    EXPECT_NE(bad_widget.message().find("constraints.curves[0].widgets[0].t"), std::string::npos) << bad_widget.message();
}
