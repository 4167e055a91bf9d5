// Issue 37 the way a hostile user meets `terrasynth` past the synth/db command line: NaN and
// infinity in every numeric flag (item 3), named pipes wherever a file is read (item 5) and a hole
// fill whose picks or cost have no end (item 4). Every refusal exits 1 (2 for bake, docs/bake.md),
// names the flag or the file and field, returns promptly (a `timeout` turns a block into a failure)
// and leaves previous outputs byte for byte as they were.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;
using nlohmann::json;

namespace {

void writeAll(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

class CliHostile : public ::testing::Test {
protected:
    void SetUp() override {
        if (!test::terrasynthBuilt()) GTEST_SKIP() << "terrasynth not built";
        test::defaultDatabase();
        dir_ = test::scratchDir(std::string("cli_hostile_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        writeProject("proj.tsyn", json::object());
        ASSERT_TRUE(writeHeightfieldPng16(path("in.png"), test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 64, 64)));
        for (const char* name : {"out.png", "out.json", "out.glb", "db.tsdb"}) writeAll(path(name), std::string("previous ") + name);
    }

    std::string path(const std::string& name) const { return dir_ + "/" + name; }

    std::string writeProject(const std::string& name, const json& extra, int size = 64) {
        json j = {{"format", "terrasynth-project"}, {"version", 1}, {"database", test::defaultDatabasePath()}, {"size", {size, size}}};
        j.update(extra);
        writeAll(path(name), j.dump(1));
        return path(name);
    }

    // Runs `terrasynth <args>` in the scratch folder and expects `code`, every word in the message,
    // and the planted outputs intact.
    void expectRefused(const std::string& args, int code, const std::vector<std::string>& words) {
        const test::CliRun r = test::runCommand("cd '" + dir_ + "' && timeout 120 " + test::binDir() + "/terrasynth " + args);
        EXPECT_EQ(r.exit_code, code) << args << "\n" << r.out;
        for (const std::string& w : words) EXPECT_NE(r.out.find(w), std::string::npos) << args << ": no \"" << w << "\" in\n" << r.out;
        EXPECT_EQ(r.out.find("terminate"), std::string::npos) << r.out;
        for (const char* name : {"out.png", "out.json", "out.glb", "db.tsdb"})
            EXPECT_EQ(test::readFile(path(name)), std::string("previous ") + name) << args << ": " << name << " changed";
        EXPECT_NE(::access(path("world").c_str(), F_OK), 0) << args << ": a bake folder was left";
    }

    std::string dir_;
};

TEST_F(CliHostile, NonFiniteNumbersAreRefusedByEveryNumericFlag) {
    struct Case {
        std::string args, flag;
        int code = 1;
    };
    const std::vector<Case> cases = {
        {"synth proj.tsyn -o out.png --level nan", "--level"},
        {"synth proj.tsyn -o out.png --level inf", "--level"},
        {"synth proj.tsyn -o out.png --seed nan", "--seed"},
        {"db build in.png -o db.tsdb --meters-per-pixel nan", "--meters-per-pixel"},
        {"db build in.png -o db.tsdb --meters-per-pixel inf", "--meters-per-pixel"},
        {"db build in.png -o db.tsdb --levels nan", "--levels"},
        {"db build in.png -o db.tsdb --threads -inf", "--threads"},
        {"export proj.tsyn -o out.glb --tile nan", "--tile"},
        {"export proj.tsyn -o out.glb --lods inf", "--lods"},
        {"export proj.tsyn -o out.glb --level nan", "--level"},
        {"export proj.tsyn -o out.glb --texture nan", "--texture"},
        {"export proj.tsyn -o out.glb --masks m_ --mask-blur inf", "--mask-blur"},
        {"export proj.tsyn -o out.glb --region 0,0,nan,8", "--region"},
        {"layers proj.tsyn --size 64,64 --mpp inf -o out.png", "--mpp"},
        {"layers proj.tsyn --size nan,64 --mpp 30 -o out.png", "--size"},
        // docs/bake.md: bad options of bake exit 2 (they exited 1 when CLI11 refused them).
        {"bake proj.tsyn -o world --tile nan", "--tile", 2},
        {"bake proj.tsyn -o world --levels inf", "--levels", 2},
        {"bake proj.tsyn -o world --threads nan", "--threads", 2},
        {"bake proj.tsyn -o world --threads 5000", "--threads", 2},
        {"bake proj.tsyn -o world --region nan,0,64,64", "--region", 2},
    };
    for (const Case& c : cases) expectRefused(c.args, c.code, {c.flag, "expected a finite number in ["});
}

TEST_F(CliHostile, NamedPipesAreRefusedWithoutBlocking) {
    // Each was opened before the regular-file check and blocked the tool for ever.
    for (const char* name : {"fifo.tsyn", "fifo.png"}) ASSERT_EQ(::mkfifo(path(name).c_str(), 0644), 0);
    // An exemplar whose sidecar is a pipe.
    ASSERT_TRUE(writeHeightfieldPng16(path("piped.png"), test::crop(test::loadExemplarField("orom_alaska"), 0, 0, 32, 32)));
    ASSERT_EQ(std::remove(path("piped.json").c_str()), 0);
    ASSERT_EQ(::mkfifo(path("piped.json").c_str(), 0644), 0);
    struct Case {
        std::string args, file;
        int code = 1;
    };
    const std::vector<Case> cases = {
        {"synth fifo.tsyn -o out.png", "fifo.tsyn"},
        {"layers fifo.tsyn", "fifo.tsyn"},
        {"export fifo.tsyn -o out.glb", "fifo.tsyn"},
        {"export --heightmap fifo.png -o out.glb", "fifo.png"},
        {"stats fifo.png", "fifo.png"},
        {"stats in.png --vs fifo.png", "fifo.png"},
        {"db build piped.png -o db.tsdb", "piped.json"},
        {"bake fifo.tsyn -o world", "fifo.tsyn", 2},
    };
    for (const Case& c : cases) expectRefused(c.args, c.code, {c.file + ": not a regular file"});
}

TEST_F(CliHostile, HoleFillPicksAndCostAreBounded) {
    // 100 000 picks ran for ever (each a generation of three quilts): refused when read.
    const json many = {{"layers", {{{"type", "hole_fill"}, {"hole", {{"shape", "ellipse"}, {"rect", {10, 10, 20, 20}}}},
                                    {"choices", std::vector<int>(100000, 1)}}}}};
    writeProject("picks.tsyn", many);
    expectRefused("layers picks.tsyn", 1, {"picks.tsyn", "choices", "100000 picks, at most 64"});
    expectRefused("synth picks.tsyn -o out.png --backend reference", 1, {"picks.tsyn", "choices", "at most 64"});
    // 64 picks are allowed, but not with the largest candidate count over a hole filling the grid:
    // refused before any quilt, naming the cost.
    const json costly = {{"layers", {{{"type", "hole_fill"}, {"hole", {{"shape", "rect"}, {"rect", {4, 4, 120, 120}}}},
                                      {"candidates", 20000}, {"choices", std::vector<int>(64, 0)}}}}};
    writeProject("costly.tsyn", costly, 128);
    expectRefused("synth costly.tsyn -o out.png --backend reference", 1, {"costly.tsyn", "choices", "would visit", "at most"});
}

}  // namespace
