// A sharded bake through a real Slurm cluster: scripts/slurm-local.sh starts a throwaway one-node
// cluster (munge + slurmctld + slurmd, state in a temp folder), scripts/bake-slurm.sh submits the
// prepare job, a 4-task array and the afterok merge, and the result must equal a single-process bake
// of the same 2048^2 region byte for byte. Skipped only where the slurm-wlm and munge binaries are
// absent (scripts/setup.sh installs them, so CI runs it).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "test_support.h"

namespace fs = std::filesystem;

namespace {

std::string repoDir() { return terrasynth::test::dataDir() + "/.."; }


int shell(const std::string& command, std::string* output) {
    const std::string log = terrasynth::test::scratchDir("bake_slurm_log") + "/out.txt";
    const int status = std::system((command + " > '" + log + "' 2>&1").c_str());
    *output = terrasynth::test::readFile(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool slurmInstalled() {
    return std::system("PATH=$PATH:/usr/sbin:/sbin; for b in sbatch scontrol sinfo slurmctld slurmd munged; do "
                       "command -v $b > /dev/null 2>&1 || exit 1; done") == 0;
}

// Starts the cluster on construction (in a short /tmp folder: munge's socket path must stay under
// the 108-byte limit of Unix sockets) and stops it, killing its daemons by pid, on destruction.
class LocalSlurm {
public:
    LocalSlurm() {
        std::string out;
        started_ = shell("'" + repoDir() + "/scripts/slurm-local.sh' start", &out) == 0;
        log_ = out;
        while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
        dir_ = out.substr(out.find_last_of('\n') + 1);
        if (started_) ::setenv("SLURM_CONF", (dir_ + "/slurm.conf").c_str(), 1);
    }
    ~LocalSlurm() {
        if (!started_) return;
        std::string out;
        shell("'" + repoDir() + "/scripts/slurm-local.sh' stop '" + dir_ + "'", &out);
        ::unsetenv("SLURM_CONF");
    }
    bool started() const { return started_; }
    const std::string& log() const { return log_; }

private:
    std::string dir_, log_;
    bool started_ = false;
};


}  // namespace

TEST(BakeSlurm, FourShardArrayEqualsASingleProcessBake) {
    if (!terrasynth::test::terrasynthBuilt()) GTEST_SKIP() << "terrasynth CLI not built";
    if (!slurmInstalled())
        GTEST_SKIP() << "slurm-wlm and munge are not installed here (sbatch, slurmctld, slurmd, munged); "
                        "scripts/setup.sh installs them";
    const std::string dir = terrasynth::test::scratchDir("bake_slurm");
    terrasynth::test::defaultDatabase();
    const nlohmann::json project = {{"format", "terrasynth-project"}, {"version", 1},
                                    {"database", terrasynth::test::defaultDatabasePath()},
                                    {"size", {2048, 2048}}, {"synthesis", {{"seed", 11}}}};
    std::ofstream(dir + "/world.tsyn") << project.dump(1);
    const std::string options = " --region 0,0,2048,2048 --tile 256 --levels 4";

    const terrasynth::test::CliRun single =
        terrasynth::test::runTerrasynth("bake '" + dir + "/world.tsyn' -o '" + dir + "/single'" + options + " --progress none");
    ASSERT_EQ(single.exit_code, 0) << single.out;

    std::string out;
    {
        LocalSlurm slurm;
        ASSERT_TRUE(slurm.started()) << slurm.log();
        const int status = shell("TERRASYNTH='" + terrasynth::test::binDir() + "/terrasynth' '" + repoDir() +
                                     "/scripts/bake-slurm.sh' '" + dir + "/world.tsyn' '" + dir +
                                     "/sharded' --shards 4 --cpus-per-task 1 --wait --" + options,
                                 &out);
        ASSERT_EQ(status, 0) << out << "\n" << terrasynth::test::readFile(dir + "/sharded.slurm-logs/merge.log");
    }
    // Every task baked its own share, and the merge ran after them.
    for (int shard = 0; shard < 4; ++shard) {
        const std::string log = terrasynth::test::readFile(dir + "/sharded.slurm-logs/shard-" + std::to_string(shard) + ".log");
        EXPECT_NE(log.find("bake shard " + std::to_string(shard) + "/4: "), std::string::npos) << log;
        EXPECT_EQ(log.find(" 0 tiles baked"), std::string::npos) << log;
    }
    EXPECT_NE(terrasynth::test::readFile(dir + "/sharded.slurm-logs/merge.log").find("tileset.json"), std::string::npos);

    const auto a = terrasynth::test::filesUnder(dir + "/single"), b = terrasynth::test::filesUnder(dir + "/sharded");
    ASSERT_EQ(a, b);
    EXPECT_GE(a.size(), 86u);  // 64 + 16 + 4 + 1 tiles, bake.json, tileset.json
    int differing = 0;
    for (const std::string& f : a)
        if (terrasynth::test::readFile(dir + "/single/" + f) != terrasynth::test::readFile(dir + "/sharded/" + f) && ++differing <= 5) ADD_FAILURE() << f << " differs";
    EXPECT_EQ(differing, 0);
}
