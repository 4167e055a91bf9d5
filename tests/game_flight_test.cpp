// The game's physics and guidance on the real synthesized world (data/default.tsyn, seed 42), no
// window: exact ground from cached blocks, the drop test, terrain following, crashes and slides.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include "terrasynth/terrain.h"
#include "terrasynth_game/autopilot.h"
#include "terrasynth_game/chase_camera.h"
#include "terrasynth_game/rings.h"
#include "terrasynth_game/exact_ground.h"
#include "terrasynth_game/flight_model.h"
#include "test_support.h"
#include "wait_until.h"

namespace terrasynth::game {
namespace {

struct World {
    std::shared_ptr<Terrain> terrain;
    HeightSource source;
    double mpp = 0.0;
    std::unique_ptr<GroundCache> cache;
    double cx = 0.0, cy = 0.0;  // world centre of the project extent

    World() {
        auto project = loadProject(test::dataDir() + "/default.tsyn");
        EXPECT_TRUE(project) << project.message();
        project->synthesis.seed = 42;
        auto opened = Terrain::fromProject(*project);
        EXPECT_TRUE(opened) << opened.message();
        terrain = *opened;
        source = [t = terrain](const PixelWindow& w, int level) { return t->heights(w, level); };
        mpp = terrain->metersPerPixel(0);
        cache = std::make_unique<GroundCache>(source, mpp);
        const PixelWindow e = terrain->extent();
        cx = (e.x + 0.5 * e.width) * mpp;
        cy = -(e.y + 0.5 * e.height) * mpp;
    }
    // Waits (a test may) until the blocks around the points are cached.
    void need(const std::vector<std::pair<double, double>>& points, double radius_m) {
        std::vector<BlockKey> keys;
        for (const auto& [x, y] : points)
            for (const BlockKey& k : cache->blocksAround(0, x, y, radius_m))
                if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
        cache->want(keys);
        ASSERT_TRUE(test::waitUntil([&] { return cache->idle(); })) << "ground blocks never arrived: " << cache->stats().last_error;
    }
    GroundQuery query() const {
        return [c = cache.get()](double x, double y) { return c->sample(x, y); };
    }
    double exact(double x, double y) const {
        auto g = exactGroundSample(source, mpp, x, y);
        EXPECT_TRUE(g) << g.message();
        return g ? g->height_m : 0.0;
    }
};

World& world() {
    static World w;
    return w;
}

TEST(GameGround, CachedBlocksGiveTheSourcesExactHeights) {
    World& w = world();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> offset(-9000.0, 9000.0);
    std::vector<std::pair<double, double>> points;
    for (int i = 0; i < 40; ++i) points.emplace_back(w.cx + offset(rng), w.cy + offset(rng));
    w.need(points, 10.0);
    for (const auto& [x, y] : points) {
        const std::optional<GroundSample> cached = w.cache->sample(x, y);
        ASSERT_TRUE(cached.has_value());
        // Windows of any size agree bit for bit, so a block and a 2x2 window give the same height.
        EXPECT_EQ(cached->height_m, w.exact(x, y)) << x << "," << y;
        EXPECT_NEAR(std::hypot(std::hypot(cached->normal[0], cached->normal[1]), cached->normal[2]), 1.0, 1e-12);
        EXPECT_GT(cached->normal[2], 0.0);
    }
    // Far from anything wanted: no answer, and no waiting for one: nothing is fetched for it (how long
    // a sample takes is not a test's to assert on a shared machine).
    const GroundCache::Stats fetched_before = w.cache->stats();
    EXPECT_FALSE(w.cache->sample(w.cx + 5e6, w.cy).has_value());
    EXPECT_TRUE(w.cache->idle());
    EXPECT_EQ(w.cache->stats().fetched, fetched_before.fetched);
    EXPECT_EQ(w.cache->stats().cached, fetched_before.cached);
}

TEST(GameGround, NormalsPointAwayFromTheSlope) {
    // East-facing slope (heights fall eastward): the normal leans east.
    const GroundSample g = groundOnCell(100.0, 90.0, 100.0, 90.0, 0.25, 0.25, 10.0);
    EXPECT_GT(g.normal[0], 0.1);
    EXPECT_NEAR(g.normal[1], 0.0, 1e-12);
    // North-facing (heights fall northward = rise southward): the normal leans north.
    const GroundSample n = groundOnCell(100.0, 100.0, 110.0, 110.0, 0.75, 0.75, 10.0);
    EXPECT_GT(n.normal[1], 0.1);
    EXPECT_DOUBLE_EQ(n.height_m, 107.5);
}

TEST(GameDrop, TwentySeededDropsComeToRestOnTheExactGround) {
    World& w = world();
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> offset(-20000.0, 20000.0);
    for (int i = 0; i < 20; ++i) {
        Body b;
        b.x = w.cx + offset(rng);
        b.y = w.cy + offset(rng);
        // A body sliding downhill can travel: keep the ground around it cached as it goes.
        w.need({{b.x, b.y}}, 3000.0);
        b.z = w.exact(b.x, b.y) + 1000.0;
        double t = 0.0;
        while (!b.at_rest && t < 600.0) {
            w.need({{b.x, b.y}}, 1500.0);
            stepBody(b, 1.0 / 30.0, w.query());
            t += 1.0 / 30.0;
        }
        ASSERT_TRUE(b.at_rest) << "drop " << i << " still moving after " << t << " s";
        EXPECT_NEAR(b.z, w.exact(b.x, b.y), 0.5) << "drop " << i;
        EXPECT_GT(t, 10.0) << "a 1000 m fall takes more than 10 s with drag";
    }
}

TEST(GameAutopilot, TwentyKilometresAtThreeHundredMetresAboveTheGround) {
    World& w = world();
    AutopilotSettings s;
    s.heading_rad = 75.0 * M_PI / 180.0;
    Autopilot pilot(s);
    Aircraft a;
    a.x = w.cx;
    a.y = w.cy;
    a.z = w.exact(a.x, a.y) + 300.0;
    a.heading = s.heading_rad;
    a.speed = 300.0;
    double min_agl = 1e9, max_agl = -1e9, flown = 0.0;
    int steps = 0, in_band = 0;
    std::vector<double> decide_ms;
    const double dt = 0.1;
    while (flown < 20000.0) {
        w.need(pilot.lookaheadPoints(a), 200.0);
        const auto t0 = std::chrono::steady_clock::now();
        const std::optional<Guidance> g = pilot.decide(a, w.query());
        decide_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        ASSERT_TRUE(g.has_value());
        const double x0 = a.x, y0 = a.y;
        ASSERT_NE(stepGuided(a, *g, dt, w.query()), StepOutcome::Crashed);
        flown += std::hypot(a.x - x0, a.y - y0);
        const double agl = a.z - w.cache->sample(a.x, a.y)->height_m;
        min_agl = std::min(min_agl, agl);
        max_agl = std::max(max_agl, agl);
        ++steps, in_band += agl > 200.0 && agl < 400.0;
    }
    std::sort(decide_ms.begin(), decide_ms.end());
    std::printf("autopilot: 20 km, above ground %.1f .. %.1f m, %.1f%% of the steps within 300 +- 100 m; decision median "
                "%.2f ms, max %.2f ms\n", min_agl, max_agl, 100.0 * in_band / steps, decide_ms[decide_ms.size() / 2],
                decide_ms.back());
    // The band is only asked where the aircraft can hold it: the course must admit a corridor
    // narrower than +-100 m under its 80 m/s^2 and 250 m/s vertical limits at 300 m/s. On the world
    // of the share blocks (issue 16, 2026-12-01) the 75-degree course admits +-95 m (a one-off
    // exhaustive search over 0.25 s vertical-speed plans on its profile); 15 of the 24 courses every
    // 15 degrees from the centre do not (walls steeper than the limits climb, docs/game.md).
    EXPECT_GE(in_band, 0.95 * steps);
    EXPECT_GT(min_agl, 150.0);
    EXPECT_LT(max_agl, 450.0);
}

TEST(GameFlight, GentleTouchSlidesHardHitCrashes) {
    // A flat plane at 1000 m.
    GroundQuery flat = [](double, double) {
        GroundSample g;
        g.height_m = 1000.0;
        return std::optional<GroundSample>(g);
    };
    FlightParams p;
    Aircraft gentle;
    gentle.z = 1000.0 + p.gear_height + 0.5;
    gentle.speed = 100.0;
    gentle.pitch = -0.05;  // 5 m/s down
    EXPECT_EQ(stepAircraft(gentle, {}, 1.0, flat, p), StepOutcome::Sliding);
    EXPECT_DOUBLE_EQ(gentle.z, 1000.0 + p.gear_height);
    EXPECT_NEAR(gentle.pitch, 0.0, 1e-9);
    Aircraft hard;
    hard.z = 1000.0 + p.gear_height + 5.0;
    hard.speed = 200.0;
    hard.pitch = -0.5;  // 96 m/s down
    EXPECT_EQ(stepAircraft(hard, {}, 1.0, flat, p), StepOutcome::Crashed);
    EXPECT_GE(hard.z, 1000.0);
    // Level flight at cruise throttle holds its height and settles to a steady speed.
    Aircraft cruise;
    cruise.z = 2000.0;
    cruise.speed = 300.0;
    for (int i = 0; i < 60; ++i) stepAircraft(cruise, {}, 1.0, flat, p);
    EXPECT_NEAR(cruise.z, 2000.0, 1e-6);
    EXPECT_NEAR(cruise.speed, p.top_speed * std::sqrt(cruise.throttle), 5.0);
    // Banking turns the aircraft.
    Aircraft turning = cruise;
    Controls right;
    right.roll = 1.0;
    stepAircraft(turning, right, 0.5, flat, p);
    stepAircraft(turning, {}, 3.0, flat, p);
    EXPECT_GT(std::remainder(turning.heading - cruise.heading, 2 * M_PI), 0.02);
}

TEST(GameCamera, NeverBelowTwoMetresAboveTheGround) {
    Aircraft a;
    a.x = 1000.0;
    a.y = 2000.0;
    a.z = 500.0;
    a.heading = 0.3;
    // Ground rising steeply behind the aircraft: the eye is lifted to 2 m above it.
    auto steep = [](double x, double y) -> std::optional<double> { return 480.0 + 1.0 * (2000.0 - y); };
    const CameraPose lifted = chaseCamera(a, steep);
    EXPECT_NEAR(lifted.eye.z(), *steep(lifted.eye.x(), lifted.eye.y()) + 2.0, 1e-9);
    // Flat ground far below: the eye stays where the chase puts it, behind and above.
    auto low = [](double, double) -> std::optional<double> { return 0.0; };
    const CameraPose free = chaseCamera(a, low);
    EXPECT_NEAR(free.eye.z(), a.z + ChaseSettings{}.above_m, 1e-9);
    EXPECT_LT((free.eye - osg::Vec3d(a.x, a.y, a.z)) * osg::Vec3d(std::sin(a.heading), std::cos(a.heading), 0.0), 0.0);
    // Unknown ground: no lift.
    const CameraPose unknown = chaseCamera(a, [](double, double) { return std::optional<double>(); });
    EXPECT_DOUBLE_EQ(unknown.eye.z(), free.eye.z());
}

TEST(GameRings, SitesFollowRidgesAndTheSeed) {
    // A north-south ridge: heights fall away east and west of column 32.
    Heightfield block(GroundCache::kBlock + 1, GroundCache::kBlock + 1, 370.4);
    for (int y = 0; y < block.height; ++y)
        for (int x = 0; x < block.width; ++x) block.at(x, y) = 2000.0f - 40.0f * std::abs(x - 32) + 0.5f * y;
    const BlockKey key{kRingLevel, 3, -2};
    const std::vector<Ring> rings = ridgeSites(block, key, 92.6, 42);
    ASSERT_FALSE(rings.empty());
    EXPECT_LE(rings.size(), static_cast<size_t>(kRingsPerBlock));
    for (const Ring& r : rings) {
        // On the crest, facing along it (north or south).
        EXPECT_NEAR(r.x, (3 * GroundCache::kBlock + 32) * 370.4, 1.0);
        EXPECT_NEAR(std::fabs(std::cos(r.facing)), 1.0, 1e-9);
    }
    // The seed decides which crest samples: same seed same rings, another seed others.
    EXPECT_EQ(ridgeSites(block, key, 92.6, 42).front().id, rings.front().id);
    bool differs = false;
    for (uint32_t seed = 1; seed < 6 && !differs; ++seed) differs = ridgeSites(block, key, 92.6, seed).front().id != rings.front().id;
    EXPECT_TRUE(differs);
    // Flying through a ring's disc counts; passing beside it does not.
    const Ring& r = rings.front();
    const double ax = std::sin(r.facing), ay = std::cos(r.facing);
    EXPECT_TRUE(passesThrough(r, r.x - 50 * ax, r.y - 50 * ay, r.z + 10, r.x + 50 * ax, r.y + 50 * ay, r.z + 10));
    EXPECT_FALSE(passesThrough(r, r.x - 50 * ax, r.y - 50 * ay, r.z + 200, r.x + 50 * ax, r.y + 50 * ay, r.z + 200));
}

TEST(GameFlight, SameInputsSameBits) {
    World& w = world();
    auto fly = [&] {
        Aircraft a;
        a.x = w.cx;
        a.y = w.cy;
        a.z = w.exact(a.x, a.y) + 400.0;
        a.speed = 250.0;
        Controls c;
        c.roll = 0.3;
        c.pitch = -0.2;
        w.need({{a.x, a.y}}, 6000.0);
        for (int i = 0; i < 100; ++i) stepAircraft(a, c, 1.0 / 30.0, w.query());
        return a;
    };
    const Aircraft a = fly(), b = fly();
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
    EXPECT_EQ(a.heading, b.heading);
}

}  // namespace
}  // namespace terrasynth::game
