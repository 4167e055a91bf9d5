// Heightmap export (PNG + sidecar, float32, GeoTIFF, EXR when built in) and type masks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>

#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

const Heightfield& rockies() {
    static const Heightfield field = test::crop(test::loadExemplarField("orom_rockies"), 40, 60, 200, 150);
    return field;
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

template <class T>
T at(const std::string& bytes, size_t offset) {
    T v;
    std::memcpy(&v, bytes.data() + offset, sizeof v);
    return v;
}

}  // namespace

TEST(ExportHeightmap, PngAndFloatRoundTripAsExemplars) {
    const std::string dir = test::scratchDir("heightmap_roundtrip");
    const HeightRange range = heightRange(rockies());
    ASSERT_TRUE(exportHeightmap(dir + "/h.png", rockies()));
    auto png = readExemplar(dir + "/h.png");
    ASSERT_TRUE(png) << png.message();
    const double step = (range.max - range.min) / 65535.0;
    for (size_t i = 0; i < rockies().size(); i += 101) ASSERT_NEAR(png->field.heights[i], rockies().heights[i], step);
    EXPECT_DOUBLE_EQ(png->field.meters_per_pixel_x, rockies().meters_per_pixel_x);

    ASSERT_TRUE(exportHeightmap(dir + "/h.f32", rockies()));
    auto f32 = readExemplar(dir + "/h.f32");
    ASSERT_TRUE(f32) << f32.message();
    EXPECT_EQ(f32->field.heights, rockies().heights);
}

TEST(ExportHeightmap, GeoTiffCarriesFloatsAndGeoreferencing) {
    const std::string dir = test::scratchDir("heightmap_tiff");
    ASSERT_TRUE(exportHeightmap(dir + "/h.tif", rockies(), 5000.0, -2000.0));
    const std::string tif = readAll(dir + "/h.tif");
    ASSERT_EQ(tif.substr(0, 2), "II");
    ASSERT_EQ(at<uint16_t>(tif, 2), 42);
    const uint32_t ifd = at<uint32_t>(tif, 4);
    const uint16_t n = at<uint16_t>(tif, ifd);
    std::map<uint16_t, std::pair<uint32_t, uint32_t>> tags;  // tag -> (count, value or offset)
    uint16_t previous = 0;
    for (uint16_t k = 0; k < n; ++k) {
        const size_t e = ifd + 2 + 12 * k;
        const uint16_t tag = at<uint16_t>(tif, e);
        EXPECT_GT(tag, previous);  // ascending, as TIFF requires
        previous = tag;
        tags[tag] = {at<uint32_t>(tif, e + 4), at<uint32_t>(tif, e + 8)};
    }
    EXPECT_EQ(tags[256].second, 200u);
    EXPECT_EQ(tags[257].second, 150u);
    EXPECT_EQ(tags[339].second & 0xFFFF, 3u);  // IEEE float
    const uint32_t data = tags[273].second;
    for (size_t i = 0; i < rockies().size(); i += 97) ASSERT_EQ(at<float>(tif, data + 4 * i), rockies().heights[i]);
    const uint32_t scale = tags[33550].second, tie = tags[33922].second;
    EXPECT_DOUBLE_EQ(at<double>(tif, scale), rockies().meters_per_pixel_x);
    EXPECT_DOUBLE_EQ(at<double>(tif, tie + 24), 5000.0);
    EXPECT_DOUBLE_EQ(at<double>(tif, tie + 32), -2000.0);
    EXPECT_EQ(tags.count(34735), 1u);
}

TEST(ExportHeightmap, ExrOnlyWhenBuiltInAndUnknownExtensionsFail) {
    const std::string dir = test::scratchDir("heightmap_exr");
    const Status exr = exportHeightmap(dir + "/h.exr", rockies());
    if (openExrAvailable()) {
        EXPECT_TRUE(exr) << exr.message();
    } else {
        ASSERT_FALSE(exr);
        EXPECT_NE(exr.message().find("OpenEXR"), std::string::npos);
    }
    const Status bad = exportHeightmap(dir + "/h.bmp", rockies());
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.message().find("h.bmp"), std::string::npos);
}

TEST(ExportMasks, OneMaskPerTypeHardAndBlurredSplat) {
    // A coordinate map in miniature: each pixel "comes from" whichever of three real exemplars is
    // relatively highest there, and each exemplar has a type (two share one).
    const Heightfield a = test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 120, 90);
    const Heightfield b = test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 120, 90);
    const Heightfield c = test::crop(test::loadExemplarField("orom_appalachians"), 0, 0, 120, 90);
    std::vector<uint8_t> sources(a.size());
    for (size_t p = 0; p < a.size(); ++p) {
        const float h[3] = {(a.heights[p] - heightRange(a).min) / (heightRange(a).max - heightRange(a).min),
                            (b.heights[p] - heightRange(b).min) / (heightRange(b).max - heightRange(b).min),
                            (c.heights[p] - heightRange(c).min) / (heightRange(c).max - heightRange(c).min)};
        sources[p] = uint8_t(std::max_element(h, h + 3) - h);
    }
    sources[5] = 255;  // kNoExemplar
    const std::vector<uint8_t> types = typesFromSources(sources, {0, 1, 0});
    EXPECT_EQ(types[5], 255);
    const std::vector<std::string> names = {"glaciated mountains", "fold/thrust belt"};
    const std::string dir = test::scratchDir("masks");
    auto hard = writeTypeMasks(dir + "/hard_", 120, 90, types, names);
    ASSERT_TRUE(hard) << hard.message();
    ASSERT_EQ(hard->size(), 2u);
    EXPECT_EQ((*hard)[1], dir + "/hard_fold_thrust_belt.png");
    auto m0 = readPng8((*hard)[0]), m1 = readPng8((*hard)[1]);
    ASSERT_TRUE(m0 && m1);
    size_t ones = 0;
    for (size_t p = 0; p < types.size(); ++p) {
        ASSERT_EQ(int(m0->samples[p]) + m1->samples[p], types[p] == 255 ? 0 : 255);
        ASSERT_EQ(m1->samples[p] == 255, types[p] == 1);
        ones += types[p] == 1;
    }
    EXPECT_GT(ones, types.size() / 10);  // both types really occur
    EXPECT_LT(ones, types.size() * 9 / 10);

    auto soft = writeTypeMasks(dir + "/soft_", 120, 90, types, names, TypeMaskOptions{3});
    ASSERT_TRUE(soft) << soft.message();
    auto s0 = readPng8((*soft)[0]), s1 = readPng8((*soft)[1]);
    size_t mixed = 0;
    for (size_t p = 0; p < types.size(); ++p) {
        ASSERT_EQ(int(s0->samples[p]) + s1->samples[p], 255);
        mixed += s0->samples[p] != 0 && s0->samples[p] != 255;
    }
    EXPECT_GT(mixed, 0u);  // transitions are blended

    auto wrong = writeTypeMasks(dir + "/x_", 10, 10, types, names);
    ASSERT_FALSE(wrong);
    EXPECT_NE(wrong.message().find("size"), std::string::npos);
}
