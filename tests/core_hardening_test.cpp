// Issue 20 at the library level of core: readers check what a file claims before allocating, say
// which file and field is wrong, and writers of a heightmap pair keep the previous pair when any
// part fails. The top-level exception guard turns anything thrown into a message.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "terrasynth/guard.h"
#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

std::string readAll(const std::string& path) {
    auto bytes = readFileBytes(path);
    return bytes ? *bytes : std::string("<missing>");
}

void writeAll(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A real 16-bit PNG exemplar (PNG bytes and sidecar JSON) of a small crop.
void writeSmallExemplar(const std::string& path, int w = 24, int h = 20) {
    ASSERT_TRUE(writeHeightfieldPng16(path, test::crop(test::loadExemplarField("orom_alaska"), 10, 10, w, h)));
}

// `png` with its IHDR claiming width x height, CRC recomputed so libpng believes it.
std::string withClaimedSize(std::string png, uint32_t width, uint32_t height) {
    auto be32 = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
    png.replace(16, 4, be32(width));
    png.replace(20, 4, be32(height));
    const uint32_t crc = crc32(crc32(0, nullptr, 0), reinterpret_cast<const Bytef*>(png.data() + 12), 17);
    png.replace(29, 4, be32(crc));
    return png;
}

TEST(CoreHardening, PngHeaderSizesAreCheckedBeforeAllocating) {
    const std::string dir = test::scratchDir("core_hardening_png");
    writeSmallExemplar(dir + "/small.png");
    const std::string png = readAll(dir + "/small.png");
    // Issue 20: a 680 KB PNG whose IHDR claims 65536 x 65536 made the reader allocate 8 GB.
    writeAll(dir + "/lie.png", withClaimedSize(png, 65536, 65536));
    auto lie = readPng16(dir + "/lie.png");
    ASSERT_FALSE(lie);
    EXPECT_TRUE(contains(lie.message(), dir + "/lie.png")) << lie.message();
    EXPECT_TRUE(contains(lie.message(), "claims 65536x65536")) << lie.message();
    // Within the side limit but more than the file can hold.
    writeAll(dir + "/big.png", withClaimedSize(png, 4000, 4000));
    auto big = readPng16(dir + "/big.png");
    ASSERT_FALSE(big);
    EXPECT_TRUE(contains(big.message(), "more than a")) << big.message();
    // Beyond the side limit.
    writeAll(dir + "/wide.png", withClaimedSize(png, 100000, 2));
    EXPECT_FALSE(readPng16(dir + "/wide.png"));
    // The honest file still reads.
    EXPECT_TRUE(readExemplar(dir + "/small.png"));
}

TEST(CoreHardening, SidecarFieldsAreReadWithoutNarrowing) {
    const std::string dir = test::scratchDir("core_hardening_sidecar");
    writeSmallExemplar(dir + "/a.png", 24, 20);
    auto side = nlohmann::json::parse(readAll(dir + "/a.json"));
    // Issue 20: width 2^32 + 24 was read with get<int>() as 24 and accepted.
    side["width"] = (uint64_t(1) << 32) + 24;
    writeAll(dir + "/a.json", side.dump());
    auto wrapped = readExemplar(dir + "/a.png");
    ASSERT_FALSE(wrapped);
    EXPECT_TRUE(contains(wrapped.message(), dir + "/a.json")) << wrapped.message();
    EXPECT_TRUE(contains(wrapped.message(), "\"width\" does not match")) << wrapped.message();
    side["width"] = 24.5;
    writeAll(dir + "/a.json", side.dump());
    EXPECT_FALSE(readExemplar(dir + "/a.png"));
}

TEST(CoreHardening, BrokenSidecarIsItsOwnErrorNotAMissingOne) {
    const std::string dir = test::scratchDir("core_hardening_broken_sidecar");
    writeSmallExemplar(dir + "/a.png");
    writeAll(dir + "/a.json", "{\"height_min_m\": 1, ");
    PlainPngScale plain;
    plain.meters_per_pixel = 30.0;
    auto broken = readExemplar(dir + "/a.png", &plain);  // even with a plain scale: the sidecar is wrong
    ASSERT_FALSE(broken);
    EXPECT_TRUE(contains(broken.message(), dir + "/a.json: malformed JSON")) << broken.message();
    EXPECT_FALSE(contains(broken.message(), "no sidecar")) << broken.message();
    std::remove((dir + "/a.json").c_str());
    auto missing = readExemplar(dir + "/a.png");
    ASSERT_FALSE(missing);
    EXPECT_TRUE(contains(missing.message(), "no sidecar")) << missing.message();
    EXPECT_TRUE(readExemplar(dir + "/a.png", &plain));
}

TEST(CoreHardening, RawFloatSidecarsAreCheckedBeforeReading) {
    const std::string dir = test::scratchDir("core_hardening_f32");
    ASSERT_TRUE(writeHeightfieldF32(dir + "/a.f32", test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 16, 12)));
    EXPECT_TRUE(readExemplar(dir + "/a.f32"));
    auto side = nlohmann::json::parse(readAll(dir + "/a.json"));
    side["width"] = 60000, side["height"] = 60000;  // 14 GB of floats claimed for a 768-byte file
    writeAll(dir + "/a.json", side.dump());
    auto claimed = readExemplar(dir + "/a.f32");
    ASSERT_FALSE(claimed);
    EXPECT_TRUE(contains(claimed.message(), "pixels")) << claimed.message();
    side["width"] = 16.5, side["height"] = 12;
    writeAll(dir + "/a.json", side.dump());
    auto fractional = readExemplar(dir + "/a.f32");
    ASSERT_FALSE(fractional);
    EXPECT_TRUE(contains(fractional.message(), "\"width\" must be a whole number")) << fractional.message();
}

TEST(CoreHardening, OnlyRegularFilesAreRead) {
    const std::string dir = test::scratchDir("core_hardening_files");
    auto folder = readFileBytes(dir);
    ASSERT_FALSE(folder);
    EXPECT_TRUE(contains(folder.message(), "is a folder")) << folder.message();
    auto device = readFileBytes("/dev/zero");  // would never end
    ASSERT_FALSE(device);
    EXPECT_TRUE(contains(device.message(), "not a regular file")) << device.message();
    writeAll(dir + "/ten", "0123456789");
    auto capped = readFileBytes(dir + "/ten", 9);
    ASSERT_FALSE(capped);
    EXPECT_TRUE(contains(capped.message(), "10 bytes")) << capped.message();
}

TEST(CoreHardening, AHeightmapPairIsReplacedTogetherOrNotAtAll) {
    const std::string dir = test::scratchDir("core_hardening_pair");
    const Heightfield before = test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 32, 32);
    const Heightfield after = test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 32, 32);
    for (const char* ext : {".png", ".f32"}) {
        const std::string path = dir + "/h" + ext;
        // The sidecar's place is taken by a non-empty folder: the image is renamed first, the
        // sidecar's rename fails, and the previous image must come back.
        ASSERT_EQ(::mkdir((dir + "/h.json").c_str(), 0755), 0);
        writeAll(dir + "/h.json/keep", "x");
        writeAll(path, "previous image");
        Status s = writeHeightfield(path, after);
        ASSERT_FALSE(s) << ext;
        EXPECT_TRUE(contains(s.message(), dir + "/h.json")) << ext << ": " << s.message();
        EXPECT_EQ(readAll(path), "previous image") << ext;
        std::system(("rm -rf '" + dir + "/h.json'").c_str());
        // A real previous pair survives a failure while staging (an unknown extension is refused
        // before anything; a file where the folder should be fails the first stage).
        ASSERT_TRUE(writeHeightfield(path, before));
        const std::string image = readAll(path), sidecar = readAll(dir + "/h.json");
        EXPECT_FALSE(writeHeightfield(path + "/h" + std::string(ext), after));
        EXPECT_EQ(readAll(path), image);
        EXPECT_EQ(readAll(dir + "/h.json"), sidecar);
        std::remove(path.c_str());
        std::remove((dir + "/h.json").c_str());
    }
    // No temporaries or backups left behind.
    EXPECT_EQ(std::system(("test -z \"$(ls -A '" + dir + "')\"").c_str()), 0);
}

TEST(CoreHardening, GuardTurnsExceptionsIntoMessages) {
    EXPECT_EQ(guarded("load", [] { return Status::ok(); }).isOk(), true);
    const Status oom = guarded("load", []() -> Status { throw std::bad_alloc(); });
    EXPECT_EQ(oom.message(), "load: out of memory (std::bad_alloc)");
    const Status length = guarded("resize", []() -> Status { throw std::length_error("vector::_M_default_append"); });
    EXPECT_TRUE(contains(length.message(), "std::length_error")) << length.message();
    const Status odd = guarded("x", []() -> Status { throw 42; });
    EXPECT_EQ(odd.message(), "x: unknown exception");
    EXPECT_EQ(runGuarded("test", []() -> int { throw std::runtime_error("boom"); }), 1);
    EXPECT_EQ(runGuarded("test", [] { return 0; }), 0);
    // A worker's exception reaches the waiting thread instead of ending the process.
    FirstException first;
    std::thread worker([&] { first.run([] { throw std::runtime_error("in a worker"); }); });
    worker.join();
    EXPECT_TRUE(first.caught());
    const Status rethrown = guarded("pool", [&] {
        first.rethrow();
        return Status::ok();
    });
    EXPECT_EQ(rethrown.message(), "pool: in a worker");
}

TEST(CoreHardening, EmptyContextAddsNothing) {
    EXPECT_EQ(Status::error("db.tsdb: cannot open").withContext("").message(), "db.tsdb: cannot open");
    EXPECT_EQ(Status::error("x").withContext("a.tsyn").message(), "a.tsyn: x");
}

}  // namespace
