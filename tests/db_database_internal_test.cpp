// The exemplar database (paper s4) on real DEMs: appearance space, PatchMatch quality, types,
// memory budget, determinism and the cache file's defences.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "db/db_internal.h"
#include "terrasynth/database.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

Exemplar exemplarFromCrop(const std::string& stem, int x0, int y0, int size, const std::string& cls) {
    Exemplar e;
    e.info.name = stem;
    e.info.terrain_class = cls;
    e.field = test::crop(test::loadExemplarField(stem), x0, y0, size, size);
    return e;
}

std::shared_ptr<const ExemplarDatabase> smallDatabase(int threads = 0) {
    std::vector<Exemplar> ex = {exemplarFromCrop("orom_alaska", 100, 100, 160, "glaciated"),
                                exemplarFromCrop("orom_appalachians", 200, 50, 128, "ridges")};
    DatabaseBuildOptions options;
    options.levels = 4;
    options.threads = threads;
    auto db = buildDatabase(std::move(ex), options);
    EXPECT_TRUE(db) << db.message();
    return db.value();
}

float decode(const DatabaseLevel& l, size_t pixel, int mode) {
    return l.appearance_offset[mode] + l.appearance_scale[mode] * l.appearance[pixel * 4 + mode];
}

}  // namespace

TEST(Database, PcaModeZeroIsTheGaussianWeightedMeanHeight) {
    auto db = smallDatabase();
    const auto& w = db::neighbourhoodWeights();
    for (int level = 0; level < db->levelCount(); ++level) {
        const DatabaseLevel& l = db->levels[level];
        const AtlasRect& r = l.rects[0];
        int checked = 0;
        for (int y = r.y + 2; y < r.y + r.height - 2; y += 3)
            for (int x = r.x + 2; x < r.x + r.width - 2; x += 3) {
                double mean = 0.0;
                for (int k = 0; k < 25; ++k)
                    mean += w[k] * l.height_m[static_cast<size_t>(y + k / 5 - 2) * l.width + x + k % 5 - 2];
                const size_t p = static_cast<size_t>(y) * l.width + x;
                ASSERT_NEAR(decode(l, p, 0), mean, l.appearance_scale[0] * 0.51 + 1e-3) << "level " << level;
                ++checked;
            }
        EXPECT_GT(checked, 0);
    }
}

TEST(Database, HeightOffsetMovesModeZeroOnly) {
    // Eq. 4-5 add h*(1 0 0 0): true only if modes 1..3 ignore a constant offset.
    Heightfield field = test::crop(test::loadExemplarField("orom_rockies"), 50, 50, 96, 96);
    Heightfield raised = field;
    for (float& h : raised.heights) h += 750.0f;
    const auto a = db::extractNeighbourhoods(field), b = db::extractNeighbourhoods(raised);
    const db::PcaBasis basis = db::fitPca({&a});
    const auto pa = db::projectFeatures(a, basis, 3), pb = db::projectFeatures(b, basis, 3);
    for (size_t i = 0; i < pa.size(); ++i) ASSERT_NEAR(pa[i], pb[i], 2e-3f);
    for (size_t i = 0; i < a.mean.size(); ++i) ASSERT_NEAR(b.mean[i] - a.mean[i], 750.0f, 2e-3f);
    // The modes carry most of the neighbourhood variance and are sorted strongest first.
    EXPECT_GT(basis.variance[0], basis.variance[1]);
    EXPECT_GT(basis.variance[1], basis.variance[3]);
}

TEST(Database, PatchMatchReaches90PercentOfBruteForceOn128) {
    Heightfield field = test::crop(test::loadExemplarField("orom_himalaya-everest"), 300, 200, 128, 128);
    const auto features = db::extractNeighbourhoods(field);
    const db::PcaBasis basis = db::fitPca({&features});
    const auto projected = db::projectFeatures(features, basis, db::kMatchModes);
    const int n = 128 * 128;
    std::vector<uint8_t> exemplar(n, 0), eligible(n, 0);
    for (int y = kInteriorMargin; y < 128 - kInteriorMargin; ++y)
        for (int x = kInteriorMargin; x < 128 - kInteriorMargin; ++x) eligible[y * 128 + x] = 1;
    db::PatchMatchInput in{128, 128, db::kMatchModes, projected.data(), exemplar.data(), eligible.data(), 7};
    const auto pm = db::patchMatch(in, 6, 2);
    const auto bf = db::bruteForceMatch(in);
    double pm_cost = 0.0, bf_cost = 0.0;
    for (uint32_t p = 0; p < static_cast<uint32_t>(n); ++p) {
        pm_cost += db::featureDistance(in, p, pm[p]);
        bf_cost += db::featureDistance(in, p, bf[p]);
        const int px = p % 128, py = p / 128, qx = pm[p] % 128, qy = pm[p] / 128;
        ASSERT_TRUE(eligible[pm[p]]) << "match on the exemplar edge";
        ASSERT_GE(std::max(std::abs(px - qx), std::abs(py - qy)), kSimilarSeparation) << "match too close to p";
    }
    const double quality = bf_cost / pm_cost;  // 1 = as good as exhaustive search
    std::printf("PatchMatch quality vs brute force: %.3f\n", quality);
    EXPECT_GE(quality, 0.90);
    EXPECT_LE(quality, 1.0 + 1e-9);
}

TEST(Database, TablesAreConsistentWithTheAtlas) {
    auto db = smallDatabase();
    ASSERT_EQ(db->levelCount(), 5);
    EXPECT_EQ(db->type_names.size(), 2u);
    for (const DatabaseLevel& l : db->levels) {
        for (size_t p = 0; p < l.pixelCount(); ++p) {
            if (l.type[p] == kNoType) continue;
            const uint32_t q = l.similar[p];
            const AtlasRect& r = l.rects[l.exemplar[q]];
            const int qx = q % l.width, qy = q / l.width;
            ASSERT_TRUE(qx >= r.x + kInteriorMargin && qx < r.x + r.width - kInteriorMargin &&
                        qy >= r.y + kInteriorMargin && qy < r.y + r.height - kInteriorMargin)
                << "C_2 on an exemplar edge";
        }
        // Seeds of each type point at interior pixels of that type.
        for (size_t t = 0; t < l.type_seeds.size(); ++t)
            for (uint32_t s : l.type_seeds[t]) ASSERT_EQ(l.type[s], t);
    }
}

TEST(Database, TypePyramidIsTheMajorityOfTheBaseBlock) {
    Exemplar e = exemplarFromCrop("orom_norway", 0, 0, 128, "fjords");
    e.type_mask.assign(128 * 128, 0);
    e.type_mask_names = {"water", "rock"};
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) e.type_mask[y * 128 + x] = (x < 40 || (y < 8 && x < 44)) ? 1 : 0;
    DatabaseBuildOptions options;
    options.levels = 3;
    auto db = buildDatabase(std::vector<Exemplar>{e}, options);
    ASSERT_TRUE(db) << db.message();
    ASSERT_EQ(db.value()->type_names.size(), 3u);  // class name + two painted names
    const DatabaseLevel& l3 = db.value()->levels[3];
    const AtlasRect& r = l3.rects[0];
    // Block (4,0) at level 3 covers base x 32..39: all "rock". Block (5,0): x 40..47, y 0..7: half rock.
    const auto& names = db.value()->type_names;
    const int rock = static_cast<int>(std::find(names.begin(), names.end(), "rock") - names.begin());
    const int water = static_cast<int>(std::find(names.begin(), names.end(), "water") - names.begin());
    EXPECT_EQ(l3.type[(r.y + 0) * l3.width + r.x + 4], rock);
    EXPECT_EQ(l3.type[(r.y + 2) * l3.width + r.x + 5], water);
    EXPECT_EQ(l3.type[(r.y + 0) * l3.width + r.x + 5], std::min(rock, water));  // 32 vs 32: tie -> lower id
}

TEST(Database, ShippedDefaultsFitThePapersMemoryBudget) {
    DatabaseBuildOptions options;
    auto db = buildDatabase({test::dataDir() + "/exemplars"}, options);
    ASSERT_TRUE(db) << db.message();
    std::printf("default database: %zu exemplars, %d levels, %.2f bytes per base pixel\n",
                db.value()->exemplars.size(), db.value()->levelCount(), db.value()->bytesPerBasePixel());
    EXPECT_EQ(db.value()->levelCount(), 7);
    EXPECT_LE(db.value()->bytesPerBasePixel(), 42.7);
    EXPECT_NEAR(db.value()->meters_per_pixel, 92.6, 1e-9);
}

TEST(Database, BuildIsDeterministicAcrossThreadCounts) {
    auto one = smallDatabase(1), two = smallDatabase(2);
    const std::string dir = test::scratchDir("db_determinism");
    ASSERT_TRUE(saveDatabase(*one, dir + "/one.tsdb"));
    ASSERT_TRUE(saveDatabase(*two, dir + "/two.tsdb"));
    EXPECT_EQ(*readFileBytes(dir + "/one.tsdb"), *readFileBytes(dir + "/two.tsdb"));
}

TEST(DatabaseCache, RoundTripAndDefences) {
    const std::string dir = test::scratchDir("db_cache");
    auto db = smallDatabase();
    const std::string path = dir + "/small.tsdb";
    ASSERT_TRUE(saveDatabase(*db, path));
    auto back = loadDatabase(path);
    ASSERT_TRUE(back) << back.message();
    EXPECT_EQ(back.value()->levels[2].similar, db->levels[2].similar);
    EXPECT_EQ(back.value()->levels[0].appearance, db->levels[0].appearance);

    const std::string bytes = *readFileBytes(path);
    ASSERT_TRUE(writeFileAtomically(dir + "/cut.tsdb", bytes.substr(0, bytes.size() - 1000)));
    auto cut = loadDatabase(dir + "/cut.tsdb");
    ASSERT_FALSE(cut);
    EXPECT_NE(cut.message().find("cut.tsdb"), std::string::npos);
    EXPECT_NE(cut.message().find("truncated"), std::string::npos) << cut.message();

    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x40;
    ASSERT_TRUE(writeFileAtomically(dir + "/flip.tsdb", flipped));
    auto flip = loadDatabase(dir + "/flip.tsdb");
    ASSERT_FALSE(flip);
    EXPECT_NE(flip.message().find("checksum"), std::string::npos) << flip.message();

    ASSERT_TRUE(writeFileAtomically(dir + "/junk.tsdb", "PNG? no."));
    auto junk = loadDatabase(dir + "/junk.tsdb");
    ASSERT_FALSE(junk);
    EXPECT_NE(junk.message().find("not a terrasynth database"), std::string::npos) << junk.message();
}

TEST(DatabaseCache, StaleOrBrokenCacheIsRebuiltNeverTrusted) {
    const std::string dir = test::scratchDir("db_stale");
    const std::string exemplar_dir = dir + "/ex";
    std::system(("mkdir -p " + exemplar_dir).c_str());
    // A small real exemplar written as PNG + sidecar so the digest covers real files.
    Heightfield field = test::crop(test::loadExemplarField("orom_gobi"), 0, 0, 96, 96);
    ExemplarInfo info{"gobi", "", "dunes", "orom_gobi crop", "see data/"};
    ASSERT_TRUE(writeHeightfieldPng16(exemplar_dir + "/gobi.png", field, &info));
    DatabaseBuildOptions options;
    options.levels = 3;
    const std::string cache = dir + "/cache.tsdb";
    bool rebuilt = false;
    std::string why;
    ASSERT_TRUE(loadOrBuildDatabase({exemplar_dir}, options, cache, &rebuilt, &why));
    EXPECT_TRUE(rebuilt);
    ASSERT_TRUE(loadOrBuildDatabase({exemplar_dir}, options, cache, &rebuilt, &why));
    EXPECT_FALSE(rebuilt);
    // Changing the inputs makes the cache stale.
    for (float& h : field.heights) h *= 1.01f;
    ASSERT_TRUE(writeHeightfieldPng16(exemplar_dir + "/gobi.png", field, &info));
    ASSERT_TRUE(loadOrBuildDatabase({exemplar_dir}, options, cache, &rebuilt, &why));
    EXPECT_TRUE(rebuilt);
    EXPECT_NE(why.find("stale"), std::string::npos) << why;
    // A truncated cache is rebuilt, and the rebuilt file is whole again.
    const std::string bytes = *readFileBytes(cache);
    ASSERT_TRUE(writeFileAtomically(cache, bytes.substr(0, bytes.size() / 2)));
    ASSERT_TRUE(loadOrBuildDatabase({exemplar_dir}, options, cache, &rebuilt, &why));
    EXPECT_TRUE(rebuilt);
    EXPECT_NE(why.find("truncated"), std::string::npos) << why;
    EXPECT_TRUE(loadDatabase(cache));
}

TEST(Database, BadInputsNameTheFile) {
    auto missing = buildDatabase(std::vector<std::string>{"/no/such/exemplar.png"}, DatabaseBuildOptions{});
    ASSERT_FALSE(missing);
    EXPECT_NE(missing.message().find("/no/such/exemplar.png"), std::string::npos);
    DatabaseBuildOptions bad;
    bad.levels = 40;
    auto absurd = buildDatabase(std::vector<std::string>{test::dataDir() + "/exemplars"}, bad);
    ASSERT_FALSE(absurd);
    EXPECT_NE(absurd.message().find("levels"), std::string::npos);
}
