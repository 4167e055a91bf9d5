// Exemplar I/O on the real shipped DEMs and on deliberately broken inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;

namespace {
void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
}  // namespace

TEST(ExemplarIo, ReadsShippedPngWithSidecarInMetres) {
    auto exemplar = readExemplar(test::dataDir() + "/exemplars/orom_alaska.png");
    ASSERT_TRUE(exemplar) << exemplar.message();
    EXPECT_EQ(exemplar->field.width, 648);
    EXPECT_EQ(exemplar->field.height, 648);
    EXPECT_DOUBLE_EQ(exemplar->field.meters_per_pixel_x, 92.6);
    EXPECT_EQ(exemplar->info.terrain_class, "glaciated mountains");
    EXPECT_NE(exemplar->info.source.find("orometry"), std::string::npos);
    // Decoding must span the sidecar's range exactly (value 0 and 65535 both occur in these DEMs).
    const HeightRange range = heightRange(exemplar->field);
    EXPECT_NEAR(range.min, 280.1112, 0.01);
    EXPECT_NEAR(range.max, 6179.8198, 0.01);
}

TEST(ExemplarIo, AnisotropicSpacingIsRead) {
    auto exemplar = readExemplar(test::sharedExemplarsDir() + "/osge_mt_fuji_90m.png");
    ASSERT_TRUE(exemplar) << exemplar.message();
    EXPECT_NEAR(exemplar->field.meters_per_pixel_x, 75.523, 1e-6);
    EXPECT_NEAR(exemplar->field.meters_per_pixel_y, 92.145, 1e-6);
}

TEST(ExemplarIo, PlainPngNeedsScaleAndUsesIt) {
    const std::string dir = test::scratchDir("plain_png");
    std::vector<uint16_t> samples = {0, 1000, 2000, 65535};
    ASSERT_TRUE(writePng16(dir + "/plain.png", 2, 2, 1, samples));
    auto without = readExemplar(dir + "/plain.png");
    ASSERT_FALSE(without);
    EXPECT_NE(without.message().find("plain.png"), std::string::npos);
    EXPECT_NE(without.message().find("vertical scale"), std::string::npos);
    PlainPngScale scale{30.0, -100.0, 0.1};
    auto with = readExemplar(dir + "/plain.png", &scale);
    ASSERT_TRUE(with) << with.message();
    EXPECT_FLOAT_EQ(with->field.at(1, 0), -100.0f + 100.0f);
    EXPECT_FLOAT_EQ(with->field.at(1, 1), static_cast<float>(-100.0 + 6553.5));
    EXPECT_DOUBLE_EQ(with->field.meters_per_pixel_y, 30.0);
}

TEST(ExemplarIo, RawFloatRoundTripAndNaNRejected) {
    const std::string dir = test::scratchDir("raw_f32");
    Heightfield field(3, 2, 25.0);
    for (size_t i = 0; i < field.heights.size(); ++i) field.heights[i] = 100.0f + 0.25f * i;
    ASSERT_TRUE(writeHeightfieldF32(dir + "/t.f32", field));
    auto back = readExemplar(dir + "/t.f32");
    ASSERT_TRUE(back) << back.message();
    EXPECT_EQ(back->field.heights, field.heights);
    EXPECT_DOUBLE_EQ(back->field.meters_per_pixel_x, 25.0);

    field.heights[4] = std::nanf("");
    std::ofstream(dir + "/t.f32", std::ios::binary)
        .write(reinterpret_cast<const char*>(field.heights.data()), field.heights.size() * 4);
    auto nan = readExemplar(dir + "/t.f32");
    ASSERT_FALSE(nan);
    EXPECT_NE(nan.message().find("t.f32"), std::string::npos);
    EXPECT_NE(nan.message().find("non-finite height at x=1 y=1"), std::string::npos) << nan.message();
}

TEST(ExemplarIo, TruncatedRawIsNamed) {
    const std::string dir = test::scratchDir("raw_truncated");
    Heightfield field(8, 8, 10.0, 5.0f);
    ASSERT_TRUE(writeHeightfieldF32(dir + "/t.f32", field));
    std::ofstream(dir + "/t.f32", std::ios::binary | std::ios::trunc).write("abcd", 4);
    auto result = readExemplar(dir + "/t.f32");
    ASSERT_FALSE(result);
    EXPECT_NE(result.message().find("truncated"), std::string::npos) << result.message();
}

TEST(ExemplarIo, CorruptAndTruncatedPngGiveClearErrors) {
    const std::string dir = test::scratchDir("corrupt_png");
    auto bytes = readFileBytes(test::dataDir() + "/exemplars/orom_rockies.png");
    ASSERT_TRUE(bytes);
    // Truncated: keep the first third.
    ASSERT_TRUE(writeFileAtomically(dir + "/cut.png", bytes->substr(0, bytes->size() / 3)));
    writeText(dir + "/cut.json", *readFileBytes(test::dataDir() + "/exemplars/orom_rockies.json"));
    auto cut = readExemplar(dir + "/cut.png");
    ASSERT_FALSE(cut);
    EXPECT_NE(cut.message().find("cut.png"), std::string::npos);
    EXPECT_NE(cut.message().find("truncated"), std::string::npos) << cut.message();
    // Garbage that is not a PNG at all.
    writeText(dir + "/junk.png", "this is not an image");
    writeText(dir + "/junk.json", "{}");
    auto junk = readExemplar(dir + "/junk.png");
    ASSERT_FALSE(junk);
    EXPECT_NE(junk.message().find("not a PNG"), std::string::npos) << junk.message();
    // Flipped bytes in the middle of the compressed data.
    std::string flipped = bytes.value();
    for (size_t i = flipped.size() / 2; i < flipped.size() / 2 + 64; ++i) flipped[i] = static_cast<char>(~flipped[i]);
    ASSERT_TRUE(writeFileAtomically(dir + "/flip.png", flipped));
    writeText(dir + "/flip.json", *readFileBytes(test::dataDir() + "/exemplars/orom_rockies.json"));
    auto flip = readExemplar(dir + "/flip.png");
    ASSERT_FALSE(flip);
    EXPECT_NE(flip.message().find("flip.png"), std::string::npos) << flip.message();
}

TEST(ExemplarIo, MalformedSidecarNamesTheField) {
    const std::string dir = test::scratchDir("bad_sidecar");
    ASSERT_TRUE(writePng16(dir + "/a.png", 2, 2, 1, {1, 2, 3, 4}));
    writeText(dir + "/a.json", "{\"height_min_m\": 0, \"height_max_m\": \"high\", \"meters_per_pixel\": 10}");
    auto a = readExemplar(dir + "/a.png");
    ASSERT_FALSE(a);
    EXPECT_NE(a.message().find("height_max_m"), std::string::npos) << a.message();
    writeText(dir + "/a.json", "{\"height_min_m\": 0, \"height_max_m\": 10, \"meters_per_pixel\": 10, ");
    auto b = readExemplar(dir + "/a.png");
    ASSERT_FALSE(b);
    EXPECT_NE(b.message().find("malformed JSON"), std::string::npos) << b.message();
    writeText(dir + "/a.json", "{\"height_min_m\": 0, \"height_max_m\": 10, \"meters_per_pixel\": -3}");
    auto c = readExemplar(dir + "/a.png");
    ASSERT_FALSE(c);
    EXPECT_NE(c.message().find("meters_per_pixel"), std::string::npos) << c.message();
}

TEST(ExemplarIo, Png16RoundTripKeepsHeightsWithinQuantisation) {
    const std::string dir = test::scratchDir("png_roundtrip");
    Heightfield field = test::crop(test::loadExemplarField("orom_himalaya-everest"), 100, 100, 64, 48);
    ASSERT_TRUE(writeHeightfieldPng16(dir + "/out.png", field));
    auto back = readExemplar(dir + "/out.png");
    ASSERT_TRUE(back) << back.message();
    const HeightRange range = heightRange(field);
    const float step = (range.max - range.min) / 65535.0f;
    for (size_t i = 0; i < field.heights.size(); ++i)
        ASSERT_NEAR(back->field.heights[i], field.heights[i], step * 0.51f + 1e-3f);
}

TEST(ExemplarIo, ListsDirectorySortedAndOnlyWithSidecars) {
    auto files = listExemplarFiles(test::dataDir() + "/exemplars");
    ASSERT_TRUE(files) << files.message();
    ASSERT_GE(files->size(), 4u);
    EXPECT_TRUE(std::is_sorted(files->begin(), files->end()));
    auto missing = listExemplarFiles("/nonexistent/dir");
    EXPECT_FALSE(missing);
    EXPECT_NE(missing.message().find("/nonexistent/dir"), std::string::npos);
}

TEST(Resample, PreservesSlopeOfAnInclinedPlane) {
    // 10 m spacing, slope 0.3 east and -0.1 south; after resampling to 25 m the slope is the same.
    Heightfield plane(200, 200, 10.0);
    for (int y = 0; y < 200; ++y)
        for (int x = 0; x < 200; ++x) plane.at(x, y) = 1000.0f + 0.3f * 10.0f * x - 0.1f * 10.0f * y;
    Heightfield coarse = resampleToSpacing(plane, 25.0);
    EXPECT_EQ(coarse.width, 80);
    const int cx = 40, cy = 40;
    const double dzdx = (coarse.at(cx + 1, cy) - coarse.at(cx - 1, cy)) / (2 * 25.0);
    const double dzdy = (coarse.at(cx, cy + 1) - coarse.at(cx, cy - 1)) / (2 * 25.0);
    EXPECT_NEAR(dzdx, 0.3, 1e-3);
    EXPECT_NEAR(dzdy, -0.1, 1e-3);
    Heightfield fine = resampleToSpacing(plane, 5.0);
    EXPECT_EQ(fine.width, 400);
    EXPECT_NEAR((fine.at(201, 200) - fine.at(199, 200)) / 10.0, 0.3, 1e-3);
}

TEST(Resample, AnisotropicFujiBecomesSquare) {
    Heightfield fuji = test::loadExemplarField("osge_mt_fuji_90m");
    Heightfield square = resampleToSpacing(fuji, 92.6);
    EXPECT_DOUBLE_EQ(square.meters_per_pixel_x, square.meters_per_pixel_y);
    EXPECT_NEAR(square.width, 1201 * 75.523 / 92.6, 1.0);
    EXPECT_NEAR(square.height, 1201 * 92.145 / 92.6, 1.0);
    // The summit keeps (most of) its height: downsampling by ~1.2 only softens the peak slightly.
    EXPECT_GT(heightRange(square).max, heightRange(fuji).max - 60.0f);
}

TEST(AtomicWrite, ExistingFileSurvivesFailedWrite) {
    const std::string dir = test::scratchDir("atomic");
    ASSERT_TRUE(writeFileAtomically(dir + "/keep.txt", "precious"));
    // Writing where a file stands in for the folder fails, naming both, and must not touch anything.
    Status s = writeFileAtomically(dir + "/keep.txt/keep.txt", "new");
    EXPECT_FALSE(s);
    EXPECT_NE(s.message().find("keep.txt/keep.txt: " + dir + "/keep.txt is a file"), std::string::npos) << s.message();
    EXPECT_EQ(*readFileBytes(dir + "/keep.txt"), "precious");
}
