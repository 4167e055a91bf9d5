// Issue 37, item 2: `terrasynth bake` as a batch scheduler and a careless user run it. Two bakes of
// the same shard at once (a requeued job beside its first attempt), two whole bakes into one
// folder, and a bake killed with SIGKILL and run again each end byte for byte as one clean bake;
// the re-run removes only a dead writer's temporaries. `bake --merge` verifies every file against
// the record its shard wrote (size, digest) and every .glb's container, and refuses damaged tiles
// with exit 2, naming them, leaving a previous tileset.json as it was. Regions beyond what synthesis
// serves or costing more than docs/limits.md allows are refused at once, before anything is written.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "temporary_names.h"
#include "test_support.h"
#include "wait_until.h"

using namespace terrasynth;
namespace fs = std::filesystem;

namespace {

const std::string kOptions = " --region 0,0,257,257 --tile 32 --levels 3 --progress none";

void writeAll(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

int countGlbs(const std::string& world) {
    int n = 0;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(world + "/tiles", ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
        n += it->path().extension() == ".glb";
    return n;
}

class BakeHostile : public ::testing::Test {
protected:
    void SetUp() override {
        if (!test::terrasynthBuilt()) GTEST_SKIP() << "terrasynth not built";
        test::defaultDatabase();
        dir_ = test::scratchDir(std::string("bake_hostile_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        const nlohmann::json project = {{"format", "terrasynth-project"}, {"version", 1},
                                        {"database", test::defaultDatabasePath()}, {"size", {512, 512}},
                                        {"synthesis", {{"seed", 9}}}};
        project_ = dir_ + "/world.tsyn";
        writeAll(project_, project.dump(1));
    }

    test::CliRun bake(const std::string& world, const std::string& extra = "") {
        return test::runTerrasynth("bake '" + project_ + "' -o '" + world + "'" + kOptions + extra);
    }
    test::CliRun merge(const std::string& world) { return test::runTerrasynth("bake --merge '" + world + "'"); }

    // Starts a bake in the background; returns the pid of the terrasynth process (its exit code
    // lands in <log>.rc when it ends).
    pid_t start(const std::string& world, const std::string& extra, const std::string& log) {
        const std::string at = dir_ + "/" + log;
        const std::string command = "(" + test::binDir() + "/terrasynth bake '" + project_ + "' -o '" + world + "'" + kOptions +
                                    extra + " > '" + at + "' 2>&1 & echo $! > '" + at + ".pid'; wait $!; echo $? > '" + at +
                                    ".rc') &";
        EXPECT_EQ(std::system(command.c_str()), 0);
        EXPECT_TRUE(test::waitUntil([&] { return !test::readFile(at + ".pid").empty(); }));
        return std::stoi(test::readFile(at + ".pid"));
    }
    // The exit code a background bake wrote when it ended (waits for it).
    int finished(const std::string& log) {
        EXPECT_TRUE(test::waitUntil([&] { return !test::readFile(dir_ + "/" + log + ".rc").empty(); })) << log << " never ended";
        return std::stoi("0" + test::readFile(dir_ + "/" + log + ".rc"));
    }

    // One clean single-process bake, the reference every other run must equal.
    std::string clean() {
        const std::string world = dir_ + "/clean";
        const test::CliRun r = bake(world);
        EXPECT_EQ(r.exit_code, 0) << r.out;
        return world;
    }

    // diff -r: the same files with the same bytes, no temporary left.
    void expectSameAs(const std::string& reference, const std::string& world) {
        const auto a = test::filesUnder(reference), b = test::filesUnder(world);
        ASSERT_EQ(a, b);
        int differing = 0;
        for (const std::string& f : a)
            if (test::readFile(reference + "/" + f) != test::readFile(world + "/" + f) && ++differing <= 5)
                ADD_FAILURE() << f << " differs";
        EXPECT_EQ(differing, 0);
    }

    std::string dir_, project_;
};

TEST_F(BakeHostile, TwoBakesOfTheSameShardAtOnceEndAsOneCleanBake) {
    const std::string reference = clean();
    const std::string world = dir_ + "/twice";
    // The second starts once the first is writing tiles, as a requeued Slurm task would; before,
    // its stale-temporary cleanup deleted the first's in-flight files ("cannot replace the file").
    start(world, " --shard 0/2 --threads 1", "first.log");
    ASSERT_TRUE(test::waitUntil([&] { return countGlbs(world) >= 3; }));
    start(world, " --shard 0/2 --threads 1", "second.log");
    EXPECT_EQ(finished("first.log"), 0) << test::readFile(dir_ + "/first.log");
    EXPECT_EQ(finished("second.log"), 0) << test::readFile(dir_ + "/second.log");
    const test::CliRun other = bake(world, " --shard 1/2");
    ASSERT_EQ(other.exit_code, 0) << other.out;
    const test::CliRun merged = merge(world);
    ASSERT_EQ(merged.exit_code, 0) << merged.out;
    expectSameAs(reference, world);
}

TEST_F(BakeHostile, TwoWholeBakesIntoOneFolderEndAsOneCleanBake) {
    const std::string reference = clean();
    const std::string world = dir_ + "/both";
    start(world, " --threads 1", "first.log");
    ASSERT_TRUE(test::waitUntil([&] { return countGlbs(world) >= 3; }));
    start(world, " --threads 1", "second.log");
    EXPECT_EQ(finished("first.log"), 0) << test::readFile(dir_ + "/first.log");
    EXPECT_EQ(finished("second.log"), 0) << test::readFile(dir_ + "/second.log");
    expectSameAs(reference, world);
}

TEST_F(BakeHostile, AKilledBakeRerunRemovesOnlyDeadWritersTemporaries) {
    const std::string reference = clean();
    const std::string world = dir_ + "/killed";
    const pid_t pid = start(world, " --threads 1", "killed.log");
    ASSERT_TRUE(test::waitUntil([&] { return countGlbs(world) >= 3; }));
    ASSERT_EQ(::kill(pid, SIGKILL), 0);
    ASSERT_TRUE(test::waitUntil([&] { return ::kill(pid, 0) != 0; }));
    // What a writer killed mid-file leaves (the killed process's name), and one of a live process
    // (this test's), which the re-run must not touch.
    const std::string tile = world + "/tiles/3/0/0.glb";
    const std::string stale = test::temporaryOf(tile, pid, 7);
    const std::string live = test::temporaryOf(tile, ::getpid());
    const std::string stale_backup = tile + ".bak." + test::hostTag() + "." + std::to_string(pid) + ".8";
    fs::create_directories(fs::path(tile).parent_path());
    for (const std::string& f : {stale, live, stale_backup}) writeAll(f, "half a tile");
    const test::CliRun rerun = bake(world);
    ASSERT_EQ(rerun.exit_code, 0) << rerun.out;
    EXPECT_NE(rerun.out.find("already complete"), std::string::npos) << rerun.out;
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_FALSE(fs::exists(stale_backup));
    ASSERT_TRUE(fs::exists(live)) << "a live process's temporary was deleted";
    fs::remove(live);
    expectSameAs(reference, world);
}

TEST_F(BakeHostile, MergeVerifiesEveryTileAndRefusesDamagedOnes) {
    const std::string reference = clean();
    const std::string world = dir_ + "/damaged";
    fs::copy(reference, world, fs::copy_options::recursive);
    const std::string previous = "previous tileset.json\n";
    writeAll(world + "/tileset.json", previous);
    const std::string leaf = "tiles/3/2/5.glb", leaf_path = world + "/" + leaf;
    const std::string good = test::readFile(leaf_path);
    auto expectRefused = [&](const std::string& context, const std::vector<std::string>& words) {
        const test::CliRun r = merge(world);
        EXPECT_EQ(r.exit_code, 2) << context << "\n" << r.out;
        for (const std::string& w : words) EXPECT_NE(r.out.find(w), std::string::npos) << context << ": no \"" << w << "\" in\n" << r.out;
        EXPECT_EQ(test::readFile(world + "/tileset.json"), previous) << context << ": tileset.json was written";
    };

    std::string flipped = good;  // one bit in the binary chunk: merge wrote tileset.json over it before
    flipped[flipped.size() - 100] ^= 1;
    writeAll(leaf_path, flipped);
    expectRefused("bit flip", {leaf, "digest", "the shard recorded"});

    writeAll(leaf_path, good.substr(0, good.size() - 4));  // truncated
    expectRefused("truncated", {leaf, "missing or incomplete"});

    writeAll(leaf_path, test::readFile(world + "/tiles/3/2/4.glb"));  // another tile's file
    expectRefused("swapped", {leaf, "the shard recorded"});

    // A damaged .glb whose record was rewritten to match: the container itself is checked.
    std::string bad_chunk = good;
    const uint32_t huge = 0x7ffffff0u;
    std::memcpy(&bad_chunk[12], &huge, 4);  // the JSON chunk's length
    writeAll(leaf_path, bad_chunk);
    std::string record_path;  // the record of the leaf's unit
    for (const std::string& f : test::filesUnder(world + "/units"))
        if (test::readFile(world + "/units/" + f).find(leaf) != std::string::npos) record_path = world + "/units/" + f;
    ASSERT_FALSE(record_path.empty());
    const std::string record = test::readFile(record_path), record_name = record_path.substr(world.size() + 1);
    {
        uint64_t h = 1469598103934665603ull;
        for (unsigned char c : bad_chunk) h = (h ^ c) * 1099511628211ull;
        char digest[17];
        std::snprintf(digest, sizeof digest, "%016llx", static_cast<unsigned long long>(h));
        nlohmann::json j = nlohmann::json::parse(record);
        for (auto& f : j["files"])
            if (f[0] == leaf) f[2] = digest;
        writeAll(record_path, j.dump());
    }
    expectRefused("bad chunk length", {leaf, "JSON chunk"});

    writeAll(leaf_path, good);
    nlohmann::json damaged_record = nlohmann::json::parse(record);
    damaged_record["files"][0][2] = "not a digest";
    writeAll(record_path, damaged_record.dump());
    expectRefused("damaged record", {record_name, "files[0]"});

    fs::remove(record_path);
    expectRefused("missing record", {record_name, "missing"});

    // Damage that a re-run of the bake mends: it re-bakes exactly what fails its record.
    writeAll(record_path, record);
    writeAll(leaf_path, flipped);
    const test::CliRun rerun = bake(world);
    ASSERT_EQ(rerun.exit_code, 0) << rerun.out;
    EXPECT_NE(rerun.out.find("1 tiles baked"), std::string::npos) << rerun.out;
    expectSameAs(reference, world);
}

TEST_F(BakeHostile, RegionsAreBoundedBeforeAnythingIsWritten) {
    const std::string world = dir_ + "/world";
    struct Case {
        std::string region, words;
    };
    const std::vector<Case> cases = {
        // allocated until std::bad_alloc (2-3 GB), then exit 1 with bake.json left behind
        {"0,0,10000000,10000000", "samples, at most 68719476736"},
        // beyond what synthesis serves: passed the check, then failed after writing files
        {"536870000,0,1000,1000", "region: must lie within +-2^28"},
        {"-268435456,-268435457,10,10", "region: must lie within +-2^28"},
        // x + width overflowed near INT64_MAX
        {"9223372036854775000,0,10,10", "--region"},
        {"0,0,131072,131072 --tile 2", "tiles, at most 4194304"},
    };
    for (const Case& c : cases) {
        const test::CliRun r = test::runTerrasynth("bake '" + project_ + "' -o '" + world + "' --region " + c.region);
        EXPECT_EQ(r.exit_code, 2) << c.region << "\n" << r.out;
        EXPECT_NE(r.out.find(c.words), std::string::npos) << c.region << ": no \"" << c.words << "\" in\n" << r.out;
        EXPECT_FALSE(fs::exists(world)) << c.region << ": something was written";
    }
    // A plan edited to such a region is refused by the merge the same way.
    const test::CliRun small = test::runTerrasynth("bake '" + project_ + "' -o '" + world + "' --region 0,0,65,65 --tile 32 --levels 2 --progress none");
    ASSERT_EQ(small.exit_code, 0) << small.out;
    nlohmann::json plan = nlohmann::json::parse(test::readFile(world + "/bake.json"));
    plan["region"] = {0, 0, 300000, 300000};
    writeAll(world + "/bake.json", plan.dump(2));
    const test::CliRun merged = merge(world);
    EXPECT_EQ(merged.exit_code, 2) << merged.out;
    EXPECT_NE(merged.out.find("bake.json"), std::string::npos) << merged.out;
    EXPECT_NE(merged.out.find("samples, at most"), std::string::npos) << merged.out;
}

}  // namespace
