// Issue 37, item 1: the edited-heights sidecar is a file users keep, copy and version, so hostile
// ones (nested 200 000 deep, a digest that is not hex, NaN heights, a frozen mask that is not 0/1,
// lifts out of range, history atlas indices past the atlas, a named pipe) are warned about, naming
// the file and the field, and the project is synthesized afresh: `terrasynth synth` exits 0 with
// exactly the heights of the project without its sidecar, and the sidecar stays byte for byte as it
// was. Also item 6: saving over a prebuilt database records that database's levels.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstring>
#include <fstream>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "terrasynth/edit_session.h"
#include "terrasynth/heightfield_io.h"
#include "test_support.h"

namespace terrasynth {
namespace {

using nlohmann::json;

constexpr int kSize = 64;

void writeAll(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

uint64_t fnv1a(const std::string& bytes) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    return h;
}

// A sidecar's parts (docs/project-format.md, "Edited heights"): "TSYNEDIT", u32 version, u64 header
// length, header JSON, blobs, u64 FNV-1a of everything before.
struct SidecarParts {
    std::string header, body;

    static SidecarParts of(const std::string& file) {
        uint64_t length = 0;
        std::memcpy(&length, file.data() + 12, 8);
        return {file.substr(20, length), file.substr(20 + length, file.size() - 28 - length)};
    }
    // The file again, with a checksum that matches whatever was changed.
    std::string file() const {
        std::string out = "TSYNEDIT";
        const uint32_t version = 1;
        const uint64_t length = header.size();
        out.append(reinterpret_cast<const char*>(&version), 4);
        out.append(reinterpret_cast<const char*>(&length), 8);
        out += header + body;
        const uint64_t sum = fnv1a(out);
        out.append(reinterpret_cast<const char*>(&sum), 8);
        return out;
    }
    // Offset in `body` of the first blob called `name`.
    size_t blobAt(const std::string& name) const {
        size_t at = 0;
        const json parsed = json::parse(header);  // kept: a range-for over a temporary's member dangles
        for (const json& b : parsed["blobs"]) {
            if (b["name"] == name) return at;
            at += b["bytes"].get<size_t>();
        }
        ADD_FAILURE() << "no blob " << name;
        return 0;
    }
};

// A session on the reference backend; `warnings` collects what it warns about.
std::unique_ptr<EditSession> open(const std::string& path, std::vector<std::string>* warnings = nullptr) {
    EditSessionOptions o;
    o.synthesizer.backend = SynthesisBackend::Reference;
    if (warnings) o.on_warning = [warnings](const std::string& w) { warnings->push_back(w); };
    auto s = EditSession::open(path, o);
    EXPECT_TRUE(s) << s.message();
    return s ? std::move(s.value()) : nullptr;
}

class EditedHeightsSidecar : public ::testing::Test {
protected:
    void SetUp() override {
        if (!test::terrasynthBuilt()) GTEST_SKIP() << "terrasynth not built";
        test::defaultDatabase();
        dir_ = test::scratchDir(std::string("sidecar_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        // A project with one point, edited in a session and saved: proj.tsyn + proj.heights.
        const json start = {{"format", "terrasynth-project"}, {"version", 1}, {"database", test::defaultDatabasePath()},
                            {"size", {kSize, kSize}}, {"synthesis", {{"seed", 5}}}};
        writeAll(dir_ + "/start.tsyn", start.dump(1));
        auto session = open(dir_ + "/start.tsyn");
        ASSERT_TRUE(session);
        PointConstraint p;
        p.x = 30, p.y = 34, p.height_m = 2500, p.radius_px = 20;
        ASSERT_TRUE(session->addPoint(p));
        p.x = 40;
        ASSERT_TRUE(session->addPoint(p));  // a second edit: the saved heights differ from a fresh build
        ASSERT_TRUE(session->save(project()));
        sidecar_ = test::readFile(sidecarPath());
        ASSERT_FALSE(sidecar_.empty());
        // What synthesizing the saved project afresh gives: the project without its sidecar.
        json fresh = json::parse(test::readFile(project()));
        fresh.erase("edited_heights");
        writeAll(dir_ + "/fresh.tsyn", fresh.dump(1));
        ASSERT_EQ(synth(dir_ + "/fresh.tsyn", dir_ + "/fresh.f32").exit_code, 0);
        fresh_ = test::readFile(dir_ + "/fresh.f32");
    }

    std::string project() const { return dir_ + "/proj.tsyn"; }
    std::string sidecarPath() const { return dir_ + "/proj.heights"; }

    // `timeout`: a reader that blocks (a named pipe) fails the test instead of hanging it.
    test::CliRun synth(const std::string& project, const std::string& out) {
        return test::runCommand("timeout 300 " + test::binDir() + "/terrasynth synth '" + project + "' -o '" + out +
                                "' --backend reference");
    }

    // Installs `bad` as the project's sidecar and expects synth to warn, naming the sidecar and
    // every word of `field`, and to give the fresh heights; the sidecar is not touched.
    void expectWarnedAndFresh(const std::string& bad, const std::string& field, const std::string& context) {
        writeAll(sidecarPath(), bad);
        const test::CliRun r = synth(project(), dir_ + "/out.f32");
        EXPECT_EQ(r.exit_code, 0) << context << "\n" << r.out;
        EXPECT_NE(r.out.find("proj.heights"), std::string::npos) << context << "\n" << r.out;
        EXPECT_NE(r.out.find(field), std::string::npos) << context << ": no \"" << field << "\" in\n" << r.out;
        EXPECT_NE(r.out.find("synthesizing the project afresh"), std::string::npos) << context << "\n" << r.out;
        EXPECT_EQ(r.out.find("terminate"), std::string::npos) << r.out;
        EXPECT_TRUE(test::readFile(dir_ + "/out.f32") == fresh_) << context << ": not the fresh synthesis";
        EXPECT_TRUE(test::readFile(sidecarPath()) == bad) << context << ": the sidecar was changed";
    }

    std::string dir_, sidecar_, fresh_;
};

TEST_F(EditedHeightsSidecar, AGoodSidecarIsUsed) {
    const test::CliRun r = synth(project(), dir_ + "/out.f32");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
    EXPECT_FALSE(test::readFile(dir_ + "/out.f32") == fresh_) << "the saved heights were not used";
}

TEST_F(EditedHeightsSidecar, HostileHeadersAreWarnedAboutNamingTheField) {
    const SidecarParts good = SidecarParts::of(sidecar_);
    ASSERT_EQ(good.file(), sidecar_);  // the test's view of the format is the format

    SidecarParts deep = good;  // the SIGSEGV: a header nested 200 000 deep
    deep.header = std::string(200000, '[') + std::string(200000, ']');
    expectWarnedAndFresh(deep.file(), "header: JSON nested more than 64 levels deep", "deep header");

    SidecarParts lifts = good;  // so were deeply nested lifts
    lifts.header = std::regex_replace(good.header, std::regex("\"lifts\":\\[[^\\]]*\\]"),
                                      "\"lifts\":" + std::string(200000, '[') + std::string(200000, ']'),
                                      std::regex_constants::format_first_only);
    ASSERT_NE(lifts.header, good.header);
    expectWarnedAndFresh(lifts.file(), "JSON nested more than 64 levels deep", "deep lifts");

    SidecarParts digest = good;  // answered only by stoull before
    digest.header = std::regex_replace(good.header, std::regex("\"digest\":\"[0-9a-f]{16}\""), "\"digest\":\"zz23456789abcdef\"");
    ASSERT_NE(digest.header, good.header);
    expectWarnedAndFresh(digest.file(), "digest: must be 16 hexadecimal digits", "digest not hex");

    SidecarParts huge_lift = good;
    huge_lift.header = std::regex_replace(good.header, std::regex("\"lifts\":\\[[^\\]]*\\]"), "\"lifts\":[1e300,0]",
                                          std::regex_constants::format_first_only);
    expectWarnedAndFresh(huge_lift.file(), "lifts: must be an array of at most", "lift out of range");

    SidecarParts extent = good;
    extent.header = std::regex_replace(good.header, std::regex("\"extent\":\\[[^\\]]*\\]"), "\"extent\":[0,0,64,99999]");
    expectWarnedAndFresh(extent.file(), "extent: must be [x, y, width, height]", "extent out of range");
}

TEST_F(EditedHeightsSidecar, NonFiniteHeightsAndAFrozenMaskThatIsNotBinaryAreRefused) {
    const SidecarParts good = SidecarParts::of(sidecar_);
    SidecarParts nan = good;  // reached the mesher's skirt precondition through the plugin
    const float not_a_number = std::nanf("");
    std::memcpy(&nan.body[good.blobAt("heights") + 4 * 100], &not_a_number, 4);
    expectWarnedAndFresh(nan.file(), "heights: value 100 is nan", "NaN height");

    SidecarParts inf = good;
    const float infinite = INFINITY;
    std::memcpy(&inf.body[good.blobAt("heights")], &infinite, 4);
    expectWarnedAndFresh(inf.file(), "heights: value 0 is inf", "infinite height");

    SidecarParts frozen = good;
    frozen.body[good.blobAt("frozen") + 7] = 7;
    expectWarnedAndFresh(frozen.file(), "frozen: pixel 7 is 7 (0 or 1)", "frozen mask");

    SidecarParts truncated = good;  // a blob shorter than the header says
    truncated.body.resize(truncated.body.size() - 16);
    expectWarnedAndFresh(truncated.file(), "truncated in the", "truncated blob");
}

TEST_F(EditedHeightsSidecar, HistoryIndicesPastTheAtlasAreRefusedAndTheNextEditWorks) {
    // These loaded, and the editor's next edit crashed (EditSession restores the history).
    SidecarParts bad = SidecarParts::of(sidecar_);
    const uint32_t past = 0xfffffff0u;
    std::memcpy(&bad.body[bad.blobAt("history.index") + 4 * 3], &past, 4);
    writeAll(sidecarPath(), bad.file());
    std::vector<std::string> warnings;
    auto session = open(project(), &warnings);
    ASSERT_TRUE(session);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("proj.heights"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("atlas index 4294967280 at pixel 3 is past the atlas"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("synthesizing the project afresh"), std::string::npos) << warnings[0];
    PointConstraint p;
    p.x = 12, p.y = 50, p.height_m = 1800, p.radius_px = 10;
    EXPECT_TRUE(session->addPoint(p));  // with the indices trusted this read past the atlas
    EXPECT_TRUE(test::readFile(sidecarPath()) == bad.file());
    // The same file without the damage opens with no warning.
    writeAll(sidecarPath(), sidecar_);
    warnings.clear();
    EXPECT_TRUE(open(project(), &warnings));
    EXPECT_TRUE(warnings.empty()) << warnings[0];
}

TEST_F(EditedHeightsSidecar, ASidecarThatIsANamedPipeDoesNotBlock) {
    // Opened before the regular-file check, it blocked synth, osgconv and the editor for ever.
    ASSERT_EQ(std::remove(sidecarPath().c_str()), 0);
    ASSERT_EQ(::mkfifo(sidecarPath().c_str(), 0644), 0);
    const test::CliRun r = synth(project(), dir_ + "/out.f32");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("proj.heights: not a regular file"), std::string::npos) << r.out;
    EXPECT_TRUE(test::readFile(dir_ + "/out.f32") == fresh_);
}

// Not a test of the fixture: it needs none of the saved project the fixture edits and synthesizes
// (a minute under the sanitizers).
TEST(EditedHeightsSidecarLevels, SavingOverAPrebuiltDatabaseRecordsItsLevels) {
    // Item 6: the editor wrote the default database_levels (6) into projects over a prebuilt
    // 3-level database; the file must say what the database it used has (levels 0..2).
    if (!test::terrasynthBuilt()) GTEST_SKIP() << "terrasynth not built";
    const std::string dir = test::scratchDir("sidecar_SavingOverAPrebuiltDatabaseRecordsItsLevels");
    ASSERT_TRUE(writeHeightfieldPng16(dir + "/small.png", test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 160, 160)));
    const test::CliRun built = test::runTerrasynth("db build '" + dir + "/small.png' -o '" + dir + "/three.tsdb' --levels 2 -q");
    ASSERT_EQ(built.exit_code, 0) << built.out;
    const json start = {{"format", "terrasynth-project"}, {"version", 1}, {"database", dir + "/three.tsdb"}, {"size", {48, 48}}};
    writeAll(dir + "/three.tsyn", start.dump(1));
    auto session = open(dir + "/three.tsyn");
    ASSERT_TRUE(session);
    ASSERT_TRUE(session->save(dir + "/three_saved.tsyn"));
    EXPECT_EQ(json::parse(test::readFile(dir + "/three_saved.tsyn"))["database_levels"], 2);
}

}  // namespace
}  // namespace terrasynth
