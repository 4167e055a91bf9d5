// `terrasynth stats` end to end: text and JSON output agree with the library, --vs resamples a terrain
// of another spacing and says so, and bad input fails with a message naming the file.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "terrasynth/heightfield_io.h"
#include "terrasynth/terrain_stats.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

test::CliRun runCli(const std::string& args) { return test::runTerrasynth("stats " + args); }
bool cliBuilt() { return test::terrasynthBuilt(); }

std::string exemplar(const std::string& stem) { return test::sharedExemplarsDir() + "/" + stem + ".png"; }

}  // namespace

TEST(StatsCli, JsonSummaryMatchesTheLibrary) {
    if (!cliBuilt()) GTEST_SKIP() << "build the terrasynth_cli target first";
    const test::CliRun r = runCli("'" + exemplar("orom_rockies") + "' --json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    auto stats = computeTerrainStats(test::loadExemplarField("orom_rockies"));
    ASSERT_TRUE(stats);
    EXPECT_EQ(j["width"], 648);
    EXPECT_DOUBLE_EQ(j["slope_deg"]["median"].get<double>(), stats->slope_deg.median);
    EXPECT_DOUBLE_EQ(j["pit_share"].get<double>(), stats->pit_share);
    EXPECT_DOUBLE_EQ(j["spectrum"]["slope_1d"].get<double>(), stats->spectrum.slope_1d);
    EXPECT_DOUBLE_EQ(j["landform_share"]["valley/channel"].get<double>(),
                     stats->landform_share[static_cast<int>(Landform::ValleyChannel)]);
}

TEST(StatsCli, VsResamplesToTheFirstTerrainsSpacingAndPrintsDistances) {
    if (!cliBuilt()) GTEST_SKIP() << "build the terrasynth_cli target first";
    const test::CliRun text = runCli("'" + exemplar("orom_rockies") + "' --vs '" + exemplar("ttb_bigtujunga") + "'");
    ASSERT_EQ(text.exit_code, 0) << text.out;
    EXPECT_NE(text.out.find("resampled"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("92.6"), std::string::npos) << text.out;
    for (int m = 0; m < kMetricCount; ++m)
        EXPECT_NE(text.out.find(metricName(static_cast<Metric>(m))), std::string::npos) << metricName(static_cast<Metric>(m));

    const test::CliRun json = runCli("'" + exemplar("orom_rockies") + "' --vs '" + exemplar("ttb_bigtujunga") + "' --json");
    ASSERT_EQ(json.exit_code, 0) << json.out;
    const nlohmann::json j = nlohmann::json::parse(json.out);
    EXPECT_NEAR(j["b"]["meters_per_pixel"][0].get<double>(), 92.6, 1e-6);
    EXPECT_GT(j["distance"]["slope"]["value"].get<double>(), 0.0);
    EXPECT_EQ(j["reference_spread"]["pairs"], 6);  // the four quadrants of the first terrain
    EXPECT_NE(j["note"].get<std::string>().find("resampled"), std::string::npos);
}

TEST(StatsCli, BadInputFailsWithTheFileName) {
    if (!cliBuilt()) GTEST_SKIP() << "build the terrasynth_cli target first";
    const test::CliRun missing = runCli("/nonexistent/dem.png");
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_NE(missing.out.find("/nonexistent/dem.png"), std::string::npos) << missing.out;

    // A heightfield too small for the statistics.
    const std::string dir = test::scratchDir("stats_cli");
    ASSERT_TRUE(writeHeightfieldF32(dir + "/tiny.f32", Heightfield(16, 16, 30.0, 5.0f)));
    const test::CliRun tiny = runCli("'" + dir + "/tiny.f32'");
    EXPECT_EQ(tiny.exit_code, 1);
    EXPECT_NE(tiny.out.find("tiny.f32"), std::string::npos) << tiny.out;
    EXPECT_NE(tiny.out.find("32x32"), std::string::npos) << tiny.out;
}
