// Issue 20 the way a hostile user meets the tool: `terrasynth` on bad inputs, bad flags, unwritable
// and full outputs. Every refusal must exit 1, name the file and field in its message, leave a
// previous output byte for byte as it was and leave no temporary behind; the legitimate inputs of
// the list must succeed.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;
using nlohmann::json;

namespace {

struct Planted {
    std::string path, bytes;
};

std::string readAll(const std::string& path) {
    auto bytes = readFileBytes(path);
    return bytes ? *bytes : std::string("<missing>");
}

void writeAll(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

class CliHardening : public ::testing::Test {
protected:
    void SetUp() override {
        if (!test::terrasynthBuilt()) GTEST_SKIP() << "terrasynth not built";
        test::defaultDatabase();  // builds the cached database the projects name
        dir_ = test::scratchDir(std::string("cli_hardening_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        db_ = test::defaultDatabasePath();
        writeProject("proj.tsyn", json::object());
        ASSERT_TRUE(writeHeightfieldPng16(dir_ + "/in.png", test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 64, 64)));
    }

    std::string path(const std::string& name) const { return dir_ + "/" + name; }

    // A 64x64 project over the default database with `extra` merged in.
    std::string writeProject(const std::string& name, const json& extra) {
        json j = {{"format", "terrasynth-project"}, {"version", 1}, {"database", db_}, {"size", {64, 64}}};
        j.update(extra);
        writeAll(path(name), j.dump(1));
        return path(name);
    }

    // Previous outputs that a refused command must leave as they were.
    std::vector<Planted> plant(const std::vector<std::string>& names) {
        std::vector<Planted> planted;
        for (const std::string& n : names) {
            planted.push_back({path(n), "previous " + n + "\n"});
            writeAll(planted.back().path, planted.back().bytes);
        }
        return planted;
    }

    void expectIntact(const std::vector<Planted>& planted, const std::string& context) {
        for (const Planted& p : planted) EXPECT_EQ(readAll(p.path), p.bytes) << context << ": " << p.path << " changed";
        const test::CliRun listing = {0, ""};
        (void)listing;
        FILE* ls = ::popen(("ls -A '" + dir_ + "'").c_str(), "r");
        char name[4096];
        while (ls && std::fgets(name, sizeof name, ls)) {
            const std::string n = name;
            EXPECT_EQ(n.find(".tmp."), std::string::npos) << context << ": temporary left behind: " << n;
            EXPECT_EQ(n.find(".bak."), std::string::npos) << context << ": backup left behind: " << n;
        }
        if (ls) ::pclose(ls);
    }

    // Runs terrasynth and expects exit 1, every word in the message and the planted files intact.
    void expectRefused(const std::string& args, const std::vector<std::string>& words, const std::vector<Planted>& planted = {}) {
        const test::CliRun r = test::runTerrasynth(args);
        EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.out;
        for (const std::string& w : words)
            EXPECT_NE(r.out.find(w), std::string::npos) << args << "\nmessage lacks \"" << w << "\":\n" << r.out;
        EXPECT_EQ(r.out.find("terminate"), std::string::npos) << r.out;
        expectIntact(planted, args);
    }

    void expectOk(const std::string& args) {
        const test::CliRun r = test::runTerrasynth(args);
        EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.out;
    }

    std::string dir_, db_;
};

// ---- Issue 20, item 1: outputs change together or not at all ----

TEST_F(CliHardening, ASecondOutputThatCannotBeWrittenLeavesTheFirstAsItWas) {
    const auto planted = plant({"out.png", "out.json"});
    const std::string synth = "synth --db " + db_ + " --size 32x32 --backend reference -o " + path("out.png");
    // A file where an output's folder should be (a missing folder is made, see below).
    expectRefused(synth + " --preview " + path("out.json/hs.png"),
                  {"terrasynth synth: --preview: ", "out.json/hs.png: " + path("out.json") + " is a file, not a folder"}, planted);
    expectRefused(synth + " --sources " + path("out.json/deeper/src.png"), {"--sources: ", "out.json/deeper/src.png"}, planted);
    expectRefused(synth + " --preview " + path("out.png"), {"--preview: ", "out.png is also written as -o"}, planted);
    expectRefused("synth --db " + db_ + " --size 32x32 -o " + path("a.f32") + " --sources " + path("a.png"),
                  {"--sources (its sidecar): ", "a.json is also written as -o (its sidecar)"}, planted);
    expectRefused("layers " + writeProject("blank.tsyn", {{"layers", {{{"type", "base"}, {"source", "blank"}, {"height_m", 5}}}}}) +
                      " --size 32,32 --mpp 30 -o " + path("out.png") + " --hillshade " + path("out.json/hs.png"),
                  {"terrasynth layers: --hillshade: ", "out.json/hs.png"}, planted);
    expectRefused("export --heightmap " + path("in.png") + " -o " + path("out.png") + " --masks " + path("out.json/m_"),
                  {"terrasynth export: --masks: "}, planted);
    // The sidecar's place taken by a folder: refused before synthesis, the image untouched.
    ASSERT_EQ(::mkdir(path("hs.json").c_str(), 0755), 0);
    const auto image = plant({"hs.png"});
    expectRefused("synth --db " + db_ + " --size 32x32 --backend reference -o " + path("hs.png"),
                  {"-o (its sidecar): ", "hs.json: is a folder"}, image);
}

// Full disks and read-only folders need a small filesystem of our own: a tmpfs mounted inside a
// private user and mount namespace (nothing is mounted for anyone else).
TEST_F(CliHardening, AFullDiskOrReadOnlyFolderLeavesThePreviousPairIntact) {
    if (!test::canMountPrivately())
        GTEST_SKIP() << "cannot mount a private tmpfs here (unshare -rm refused: no user namespaces); "
                        "the rename-failure cases of ASecondOutputThatCannotBeWritten... still ran";
    // The previous pair: a real heightmap and sidecar, kept outside the small filesystem too.
    ASSERT_TRUE(writeHeightfieldPng16(path("old.png"), test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 48, 48)));
    ::mkdir(path("small").c_str(), 0755);
    for (const char* mode : {"full", "readonly"}) {
        const std::string script = path(std::string("run_") + mode + ".sh");
        writeAll(script,
                 "set -e\n"
                 "D='" + path("small") + "'\n"
                 "mount -t tmpfs -o size=256k tmpfs \"$D\"\n"
                 "cp '" + path("old.png") + "' \"$D/out.png\"\n"
                 "cp '" + path("old.json") + "' \"$D/out.json\"\n" +
                     (std::string(mode) == "full" ? "dd if=/dev/zero of=\"$D/filler\" bs=4k 2>/dev/null || true\n"
                                                  : "mount -o remount,ro \"$D\"\n") +
                     "set +e\n'" + test::binDir() + "/terrasynth' synth --db '" + db_ +
                     "' --size 64x64 --backend reference -o \"$D/out.png\" --preview \"$D/hs.png\" > '" +
                     path(std::string("log_") + mode) + "' 2>&1\n"
                     "echo $? > '" + path(std::string("rc_") + mode) + "'\n"
                     "cmp \"$D/out.png\" '" + path("old.png") + "' && cmp \"$D/out.json\" '" + path("old.json") +
                     "' && echo intact > '" + path(std::string("cmp_") + mode) + "'\n"
                     "ls -A \"$D\" > '" + path(std::string("ls_") + mode) + "'\n");
        ASSERT_EQ(std::system(("unshare -rm sh '" + script + "'").c_str()), 0) << mode;
        const std::string log = readAll(path(std::string("log_") + mode));
        EXPECT_EQ(readAll(path(std::string("rc_") + mode)), "1\n") << mode << ": " << log;
        EXPECT_EQ(readAll(path(std::string("cmp_") + mode)), "intact\n") << mode << ": " << log;
        std::string expected_files = std::string(mode) == "full" ? "filler\nout.json\nout.png\n" : "out.json\nout.png\n";
        EXPECT_EQ(readAll(path(std::string("ls_") + mode)), expected_files) << mode << ": temporaries left";
        EXPECT_NE(log.find(std::string(mode) == "full" ? "write failed (disk full?)" : "cannot write in"), std::string::npos)
            << mode << ": " << log;
        std::printf("%s: %s", mode, log.c_str());
    }
}

// ---- Item 2: nothing is thrown out of the program ----

TEST_F(CliHardening, ExemplarNamesThatAreNotUtf8AreWrittenNotThrown) {
    // Issue 20: a file name with a non-UTF-8 byte ended in nlohmann's type_error and SIGABRT when
    // written into the --sources sidecar.
    const std::string ex = path("latin1");
    ::mkdir(ex.c_str(), 0755);
    ASSERT_TRUE(writeHeightfieldPng16(ex + "/caf\xe9.png", test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 80, 80)));
    expectOk("db build " + ex + " -o " + path("latin1.tsdb") + " --levels 2 -q");
    expectOk("synth --db " + path("latin1.tsdb") + " --size 16x16 --backend reference -o " + path("o.png") + " --sources " +
             path("s.png"));
    auto side = json::parse(readAll(path("s.json")), nullptr, false);
    ASSERT_FALSE(side.is_discarded());
    EXPECT_NE(side.dump().find("caf\xef\xbf\xbd"), std::string::npos) << side.dump();  // U+FFFD
}

// ---- Items 3, 6, 8, 9: limits and small things ----

TEST_F(CliHardening, AbsurdSizesAreRefusedBeforeAllocating) {
    const auto planted = plant({"out.png", "out.json"});
    // A PNG whose header claims 65536 x 65536 (CRC fixed up).
    std::string png = readAll(path("in.png"));
    png.replace(16, 8, std::string("\x00\x01\x00\x00\x00\x01\x00\x00", 8));
    writeAll(path("lie.png"), png);
    std::system(("cp '" + path("in.json") + "' '" + path("lie.json") + "'").c_str());
    expectRefused("export --heightmap " + path("lie.png") + " -o " + path("out.png"), {"terrasynth export: ", "lie.png"}, planted);
    expectRefused("db build " + test::dataDir() + "/exemplars -o " + path("fine.tsdb") + " --meters-per-pixel 0.001 -q",
                  {"terrasynth db build: ", "orom_", "coarser --meters-per-pixel"});
    const std::string layers = "layers " + writeProject("fbm.tsyn", {{"layers", {{{"type", "base"}, {"source", "fbm"}}}}});
    expectRefused(layers + " --size=-64,64 --mpp 30 -o " + path("out.png"), {"terrasynth layers: --size: expected a finite number in [1, 16384], got '-64'"},
                  planted);
    expectRefused(layers + " --size 100000,100000 --mpp 30 -o " + path("out.png"), {"--size"}, planted);
    expectRefused("synth " + writeProject("curve.tsyn", {{"constraints", {{"curves", {{{"course", {{0, 0}, {1e9, 1}}},
                                                                                      {"widgets", {{{"t", 0}, {"height_m", 9}}}}}}}}}}) +
                      " -o " + path("out.png"),
                  {"curve.tsyn: constraints.curves[0].course[1]: beyond +-2^28"}, planted);
    expectRefused("synth " + writeProject("paste.tsyn", {{"constraints", {{"pastes", {{{"source", {{0, 0}, {9, 0}, {9, 9}}},
                                                                                      {"target", {-1e9, 0}}}}}}}}) +
                      " -o " + path("out.png"),
                  {"paste.tsyn: constraints.pastes[0].target: beyond"}, planted);
}

TEST_F(CliHardening, OriginsBeyondTheGridAreRefusedTheSameWayEverywhere) {
    const auto planted = plant({"out.png", "out.json"});
    const std::string synth = "synth " + path("proj.tsyn") + " --backend reference -o " + path("out.png");
    expectRefused(synth + " --origin=-9223372036854775808,0", {"proj.tsyn: origin: must be within +-2^28"}, planted);
    expectRefused(synth + " --origin 268435457,0", {"origin: must be within +-2^28"}, planted);
    expectRefused("synth " + writeProject("far.tsyn", {{"origin", {0, 268435457}}}) + " -o " + path("out.png"),
                  {"far.tsyn: origin: must be within +-2^28"}, planted);
    expectOk("synth " + writeProject("edge.tsyn", {{"origin", {-268435456, 268435456}}, {"size", {8, 8}}}) +
             " --backend reference -o " + path("edge.png"));
    expectOk("synth " + path("proj.tsyn") + " --backend reference --origin=-268435456,268435456 --size 8x8 -o " +
             path("edge2.png"));
}

TEST_F(CliHardening, DeepJsonIsRefused) {
    writeAll(path("deep.tsyn"), "{\"constraints\": {\"points\": " + std::string(100000, '[') + std::string(100000, ']') + "}}");
    expectRefused("synth " + path("deep.tsyn") + " -o " + path("o.png"), {"deep.tsyn: JSON nested more than 64 levels deep"});
}

TEST_F(CliHardening, SmallerMessagesNameWhatIsWrong) {
    // --db errors had an empty context ("synth: : file").
    const test::CliRun db = test::runTerrasynth("synth --db " + path("none.tsdb") + " -o " + path("o.png"));
    EXPECT_EQ(db.exit_code, 1);
    EXPECT_NE(db.out.find("terrasynth synth: " + path("none.tsdb") + ": cannot open"), std::string::npos) << db.out;
    EXPECT_EQ(db.out.find(": :"), std::string::npos) << db.out;
    // A malformed sidecar was reported as "no sidecar".
    writeAll(path("in.json"), "{\"height_min_m\": ");
    expectRefused("export --heightmap " + path("in.png") + " -o " + path("o.tif"), {"in.json: malformed JSON"});
    // A folder given as the project was "malformed JSON".
    expectRefused("synth " + dir_ + " -o " + path("o.png"), {dir_ + ": is a folder, not a file"});
    // An unknown subcommand printed "A subcommand is required".
    expectRefused("frobnicate", {"terrasynth: unknown command \"frobnicate\" (commands: db, synth, layers, stats, export, bake)"});
    expectRefused("db frob x", {"terrasynth db: unknown command \"frob\" (commands: build)"});
}

// ---- Item 5: valid arguments succeed ----

TEST_F(CliHardening, ExportWithASliverTileSucceeds) {
    ASSERT_TRUE(writeHeightfieldPng16(path("h256.png"), test::crop(test::loadExemplarField("orom_rockies"), 0, 0, 256, 256)));
    expectOk("export --heightmap " + path("h256.png") + " -o " + path("t.glb") + " --tile 254 --lods 2");
    expectOk("export --heightmap " + path("h256.png") + " -o " + path("t.gltf") + " --tile 254 --lods 3 --lod-method simplify");
}

TEST_F(CliHardening, EveryWriterMakesTheFoldersOfItsOutputs) {
    // Each command writes into folders that do not exist yet, two deep; the files land there.
    const std::string synth = "synth --db " + db_ + " --size 32x32 --backend reference";
    expectOk(synth + " -o " + path("s/a/out.png") + " --preview " + path("s/b/hs.png") + " --sources " + path("s/c/src.png"));
    expectOk(synth + " -o " + path("s/d/out.tif"));
    expectOk("db build " + path("in.png") + " -o " + path("d/a/db.tsdb") + " --levels 2");
    const std::string blank = writeProject("blank.tsyn", {{"layers", {{{"type", "base"}, {"source", "blank"}, {"height_m", 5}}}}});
    expectOk("layers " + blank + " --size 32,32 --mpp 30 -o " + path("l/a/out.png") + " --hillshade " + path("l/b/hs.png"));
    const std::string project = path("proj.tsyn");
    expectOk("export " + project + " -o " + path("e/a/t.glb") + " --lods 2 --masks " + path("e/m/mask_"));
    expectOk("export --heightmap " + path("in.png") + " -o " + path("e/b/t.tif"));
    expectOk("export " + project + " --preset unreal -o " + path("e/u/terrain.png"));
    for (const char* file : {"s/a/out.png", "s/a/out.json", "s/b/hs.png", "s/c/src.png", "s/d/out.tif", "d/a/db.tsdb", "l/a/out.png",
                             "l/b/hs.png", "e/a/t.glb", "e/a/t_lod1.glb", "e/b/t.tif", "e/u/terrain.png"})
        EXPECT_NE(readAll(path(file)), "<missing>") << file;
    EXPECT_EQ(std::system(("ls " + path("e/m") + "/mask_*.png >/dev/null").c_str()), 0) << "no masks in e/m";
    expectIntact({}, "every writer");  // no temporaries left
}

// ---- The cases the tool already handled, kept as regressions (reconstructed from its messages) ----

TEST_F(CliHardening, RefusedInputsNameTheFileAndTheField) {
    const auto planted = plant({"out.png", "out.json"});
    const std::string out = " -o " + path("out.png");
    auto project = [&](const std::string& name, const json& extra) { return writeProject(name, extra); };
    struct Case {
        std::string args;
        std::vector<std::string> words;
    };
    const std::vector<Case> cases = {
        {"synth" + out, {"terrasynth synth: give a project file or --db database.tsdb"}},
        {"synth " + path("nope.tsyn") + out, {"nope.tsyn: cannot open"}},
        {"synth " + path("proj.tsyn") + " --size 0x5" + out, {"--size must be WxH with sides 1..16384"}},
        {"synth " + path("proj.tsyn") + " --size 20000x20" + out, {"--size must be WxH"}},
        {"synth " + path("proj.tsyn") + " --size ax3" + out, {"--size must be WxH"}},
        {"synth " + path("proj.tsyn") + " --origin '1;2'" + out, {"--origin must be X,Y"}},
        {"synth " + path("proj.tsyn") + " --backend cuda" + out, {"--backend must be opencl or reference"}},
        {"synth " + path("proj.tsyn") + " --level 13" + out, {"terrasynth synth: --level: expected a finite number in [0, 12], got '13'"}},
        {"synth " + path("proj.tsyn") + " --seed x" + out, {"terrasynth synth: --seed: expected a finite number in [0, 4294967295], got 'x'"}},
        {"synth " + path("proj.tsyn") + " -o " + path("out.bmp"), {"out.bmp: unknown heightmap extension \".bmp\""}},
        {"synth " + path("proj.tsyn") + out + " --preview " + path("hs.jpg"), {"--preview: ", "hs.jpg: must end in .png"}},
        {"synth " + path("proj.tsyn") + out + " --unknown-flag", {"terrasynth synth: The following argument"}},
        {"synth " + project("json.tsyn", json::object()) + "x" + out, {"json.tsynx: cannot open"}},
        {"synth " + project("typo.tsyn", {{"seeed", 3}}) + out, {"typo.tsyn: seeed: unknown field"}},
        {"synth " + project("version.tsyn", {{"version", 99}}) + out, {"version.tsyn: version: project version 99 is newer"}},
        {"synth " + project("jitter.tsyn", {{"synthesis", {{"jitter", 2}}}}) + out, {"jitter.tsyn: synthesis.jitter: must be in [0, 1]"}},
        {"synth " + project("passes.tsyn", {{"synthesis", {{"correction_passes", 9}}}}) + out, {"synthesis.correction_passes: must be in 0..4"}},
        {"synth " + project("size.tsyn", {{"size", {0, 64}}}) + out, {"size.tsyn: size: each side must be 1..16384"}},
        {"synth " + project("radius.tsyn", {{"constraints", {{"points", {{{"x", 1}, {"y", 1}, {"height_m", 5}, {"radius_px", 0}}}}}}}) + out,
         {"radius.tsyn: constraints.points[0].radius_px: must be in [0.001, 1000000], got 0"}},
        {"synth " + project("type.tsyn", {{"constraints", {{"types", {{"strokes", {{{"type", "moon"}, {"points", {{1, 1}}}}}}}}}}}) + out,
         {"type.tsyn: constraints.types.strokes[0].type: unknown terrain type \"moon\""}},
        {"synth " + project("sorted.tsyn", {{"constraints", {{"curves", {{{"course", {{0, 0}, {9, 9}}},
                                                                        {"widgets", {{{"t", 0.5}, {"height_m", 1}}, {{"t", 0.1}, {"height_m", 1}}}}}}}}}}) + out,
         {"sorted.tsyn: constraints.curves[0].widgets[1].t: widgets must be sorted by t"}},
        {"synth " + project("pts.tsyn", {{"constraints", {{"points", 5}}}}) + out, {"pts.tsyn: constraints.points: must be an array"}},
        {"synth " + project("section.tsyn", {{"constraints", {{"rivers", json::array()}}}}) + out,
         {"section.tsyn: constraints.rivers: not supported"}},
        {"synth " + project("layer.tsyn", {{"layers", {{{"type", "volcano"}}}}}) + out, {"layer.tsyn", "unknown layer type \"volcano\""}},
        {"synth " + project("nodb.tsyn", {{"database", path("missing.tsdb")}}) + out, {"missing.tsdb: cannot open"}},
        {"db build " + path("nothing") + " -o " + path("x.tsdb"), {"terrasynth db build: ", "nothing"}},
        {"db build " + dir_ + " -o " + path("x.tsdb") + " --levels 0", {"--levels: expected a finite number in [1, 12], got '0'"}},
        {"db build " + path("proj.tsyn") + " -o " + path("x.tsdb"), {"proj.tsyn: unsupported exemplar format \".tsyn\""}},
        {"layers " + path("nope.tsyn"), {"terrasynth layers: ", "nope.tsyn: cannot open"}},
        {"layers " + path("proj.tsyn") + " --mpp -1 --size 4,4" + out, {"--mpp: expected a finite number in [0.000001, 100000], got '-1'"}},
        {"export " + path("proj.tsyn") + " --heightmap " + path("in.png") + out, {"give either a project or --heightmap"}},
        {"export --heightmap " + path("in.png") + " -o " + path("t.glb") + " --lod-method foo", {"--lod-method: expected grid or simplify"}},
        {"export --heightmap " + path("in.png") + " -o " + path("t.glb") + " --region 1,2,3", {"--region: expected X,Y,W,H"}},
        {"export --heightmap " + path("in.png") + " -o " + path("t.glb") + " --tile 0", {"--tile: expected a finite number in [1, 4096], got '0'"}},
        {"export --heightmap " + path("in.png") + " -o " + path("t.obj"), {"t.obj: unknown heightmap extension \".obj\""}},
        {"export --heightmap " + path("in.png") + " --masks " + path("m_") + out, {"--masks needs a project"}},
        {"stats " + path("nope.png"), {"terrasynth stats: ", "nope.png"}},
    };
    for (const Case& c : cases) expectRefused(c.args, c.words, planted);
}

}  // namespace
