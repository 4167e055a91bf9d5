// Issue 20: a database file with a valid checksum proves nothing about who wrote it. Each case
// breaks one invariant the synthesis kernels rely on, saves the file (checksum recomputed) and
// expects the loader to refuse it, naming the file, the level and the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "terrasynth/database.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

// Two real exemplar crops, three levels: small enough to build in a blink.
std::shared_ptr<const ExemplarDatabase> tinyDatabase() {
    static std::shared_ptr<const ExemplarDatabase> db = [] {
        std::vector<Exemplar> exemplars(2);
        exemplars[0].info.name = "alaska", exemplars[0].info.terrain_class = "glaciated mountains";
        exemplars[0].field = test::crop(test::loadExemplarField("orom_alaska"), 100, 100, 48, 40);
        exemplars[1].info.name = "rockies", exemplars[1].info.terrain_class = "alpine ranges";
        exemplars[1].field = test::crop(test::loadExemplarField("orom_rockies"), 200, 50, 36, 44);
        DatabaseBuildOptions options;
        options.levels = 2;
        auto built = buildDatabase(std::move(exemplars), options);
        EXPECT_TRUE(built) << built.message();
        return built ? *built : nullptr;
    }();
    return db;
}

// Saves a copy of the tiny database broken by `breakIt` and loads it back.
Result<std::shared_ptr<const ExemplarDatabase>> loadBroken(const std::string& name,
                                                           const std::function<void(ExemplarDatabase&)>& breakIt) {
    ExemplarDatabase copy = *tinyDatabase();
    breakIt(copy);
    const std::string path = test::scratchDir("db_hardening_" + name) + "/broken.tsdb";
    EXPECT_TRUE(saveDatabase(copy, path));
    auto loaded = loadDatabase(path);
    if (!loaded) {
        EXPECT_NE(loaded.message().find(path), std::string::npos) << "the message names the file";
    }
    return loaded;
}

void expectRefused(const std::string& name, const std::string& problem, const std::function<void(ExemplarDatabase&)>& breakIt) {
    auto loaded = loadBroken(name, breakIt);
    ASSERT_FALSE(loaded) << name << ": the loader accepted it";
    EXPECT_NE(loaded.message().find(problem), std::string::npos) << name << ": " << loaded.message();
}

// The pixel index of exemplar e's rectangle corner at a level, plus (dx, dy).
uint32_t inRect(const DatabaseLevel& l, size_t e, int dx, int dy) {
    const AtlasRect& r = l.rects[e];
    return static_cast<uint32_t>((r.y + dy) * l.width + r.x + dx);
}

TEST(DatabaseHardening, TheUntouchedDatabaseLoads) {
    auto loaded = loadBroken("untouched", [](ExemplarDatabase&) {});
    ASSERT_TRUE(loaded) << loaded.message();
    EXPECT_EQ((*loaded)->levelCount(), tinyDatabase()->levelCount());
}

TEST(DatabaseHardening, CraftedDatabasesOfIssue20AreRefused) {
    // The four files valgrind caught in the reference backend (issue 20, item 4).
    expectRefused("nan_scale", "appearance mode 0",
                  [](ExemplarDatabase& d) { d.levels[0].appearance_scale[0] = std::numeric_limits<float>::quiet_NaN(); });
    expectRefused("zero_width_rect", "rectangle", [](ExemplarDatabase& d) { d.levels[1].rects[0].width = 0; });
    expectRefused("all_255", "names another exemplar", [](ExemplarDatabase& d) {
        for (DatabaseLevel& l : d.levels) std::fill(l.exemplar.begin(), l.exemplar.end(), uint8_t(255));
    });
    expectRefused("no_seed_lists", "no seed coordinates", [](ExemplarDatabase& d) { d.levels[2].type_seeds.clear(); });
}

TEST(DatabaseHardening, EveryKernelInvariantIsChecked) {
    expectRefused("zero_scale", "appearance mode 2", [](ExemplarDatabase& d) { d.levels[0].appearance_scale[2] = 0.0f; });
    expectRefused("inf_offset", "appearance mode 1",
                  [](ExemplarDatabase& d) { d.levels[1].appearance_offset[1] = std::numeric_limits<float>::infinity(); });
    expectRefused("nan_height", "height", [](ExemplarDatabase& d) {
        d.levels[0].height_m[inRect(d.levels[0], 0, 3, 3)] = std::numeric_limits<float>::quiet_NaN();
    });
    expectRefused("tiny_rect", "smaller than 5x5", [](ExemplarDatabase& d) { d.levels[0].rects[1].height = 3; });
    expectRefused("rect_outside", "outside the atlas", [](ExemplarDatabase& d) { d.levels[0].rects[1].x = d.levels[0].width - 2; });
    expectRefused("wrong_exemplar", "names another exemplar",
                  [](ExemplarDatabase& d) { d.levels[0].exemplar[inRect(d.levels[0], 0, 2, 2)] = 1; });
    expectRefused("unknown_type", "unknown type", [](ExemplarDatabase& d) { d.levels[0].type[inRect(d.levels[0], 1, 4, 4)] = 200; });
    expectRefused("similar_in_gutter", "similarity table", [](ExemplarDatabase& d) {
        DatabaseLevel& l = d.levels[0];
        l.similar[inRect(l, 0, 5, 5)] = inRect(l, 0, 0, 0);  // an exemplar edge: candidates read one pixel beyond it
    });
    expectRefused("similar_out_of_range", "similarity", [](ExemplarDatabase& d) { d.levels[1].similar[0] = 0xFFFFFFFFu; });
    expectRefused("seed_on_edge", "type seed", [](ExemplarDatabase& d) {
        DatabaseLevel& l = d.levels[1];
        for (auto& list : l.type_seeds)
            if (!list.empty()) list[0] = inRect(l, 0, 1, 0);
    });
    expectRefused("more_seed_lists_than_types", "more seed lists",
                  [](ExemplarDatabase& d) { d.levels[0].type_seeds.resize(d.type_names.size() + 1); });
    expectRefused("pixels_name_missing", "missing exemplar", [](ExemplarDatabase& d) {
        d.levels.back().rects[1] = AtlasRect{};  // its gutter pixels still name it
    });
    expectRefused("exemplar_vanishes", "missing below", [](ExemplarDatabase& d) { d.levels[0].rects[1] = AtlasRect{}; });
    expectRefused("no_levels", "no pyramid levels", [](ExemplarDatabase& d) { d.levels.clear(); });
    expectRefused("nan_spacing", "meters_per_pixel",
                  [](ExemplarDatabase& d) { d.meters_per_pixel = std::numeric_limits<double>::quiet_NaN(); });
    expectRefused("no_types", "no exemplars or no terrain types", [](ExemplarDatabase& d) {
        d.type_names.clear();
        d.exemplar_type.assign(d.exemplars.size(), 0);
    });
    expectRefused("exemplar_type", "exemplar type out of range", [](ExemplarDatabase& d) { d.exemplar_type[0] = 7; });
}

TEST(DatabaseHardening, AbsurdSpacingIsRefusedBeforeResampling) {
    // Issue 20: `db build --meters-per-pixel 0.001` ran out of memory after 46 s.
    std::vector<Exemplar> exemplars(1);
    exemplars[0].info.path = "alaska.png";
    exemplars[0].field = test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 64, 64);
    DatabaseBuildOptions options;
    options.meters_per_pixel = 0.001;
    auto built = buildDatabase(std::move(exemplars), options);
    ASSERT_FALSE(built);
    EXPECT_NE(built.message().find("alaska.png"), std::string::npos) << built.message();
    EXPECT_NE(built.message().find("coarser --meters-per-pixel"), std::string::npos) << built.message();
}

}  // namespace
