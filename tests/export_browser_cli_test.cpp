// A baked world in a browser: scripts/view_world.sh serves it with CesiumJS, Debian's headless
// Chromium (software GL) loads every tile the view needs, and the screenshot shows terrain, not the
// clear colour. Skipped, with the reason, only where chromium or node is not installed
// (scripts/setup.sh installs them; cesium and playwright-core come with `npm ci --prefix scripts`).
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "terrasynth/heightfield_io.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

std::string repoDir() { return test::dataDir() + "/.."; }

}  // namespace

TEST(BrowserView, CesiumShowsTheBakedTerrainInHeadlessChromium) {
    if (!test::haveProgram("chromium")) GTEST_SKIP() << "chromium is not installed (Debian chromium, scripts/setup.sh)";
    if (!test::haveProgram("node")) GTEST_SKIP() << "node is not installed (scripts/setup.sh)";
    for (const char* module : {"cesium", "playwright-core"})
        ASSERT_FALSE(test::readFile(repoDir() + "/scripts/node_modules/" + module + "/package.json").empty())
            << module << " is not installed: run `npm ci --prefix scripts` in the repository";

    const std::string dir = test::scratchDir("browser_view");
    const std::string project = test::defaultDatabaseProject(dir, 3);
    const test::CliRun bake =
        test::runTerrasynth("bake '" + project + "' -o '" + dir + "/world' --region 0,0,513,513 --tile 128 --levels 3 --progress none");
    ASSERT_EQ(bake.exit_code, 0) << bake.out;

    const std::string shot = dir + "/view.png";
    const test::CliRun view = test::runCommand("'" + repoDir() + "/scripts/view_world.sh' '" + dir + "/world' --screenshot '" + shot + "'");
    ASSERT_EQ(view.exit_code, 0) << view.out;
    const size_t brace = view.out.rfind('{');
    ASSERT_NE(brace, std::string::npos) << view.out;
    const nlohmann::json report = nlohmann::json::parse(view.out.substr(brace), nullptr, false);
    ASSERT_TRUE(report.is_object()) << view.out;
    std::printf("Chromium + CesiumJS: every tile of the view loaded in %.1f s\n", report["seconds"].get<double>());
    EXPECT_TRUE(report["elsewhere"].empty()) << "requests that left localhost: " << report["elsewhere"].dump();

    auto image = readPng8(shot);
    ASSERT_TRUE(image) << image.message();
    ASSERT_GE(image->channels, 3);
    const int clear[3] = {report["clearColor"][0].get<int>(), report["clearColor"][1].get<int>(), report["clearColor"][2].get<int>()};
    size_t background = 0;
    double sum = 0.0, sum2 = 0.0;
    const size_t pixels = size_t(image->width) * image->height;
    for (size_t p = 0; p < pixels; ++p) {
        const uint8_t* c = &image->samples[p * image->channels];
        bool same = true;
        for (int k = 0; k < 3; ++k) same = same && std::abs(int(c[k]) - clear[k]) <= 3;
        background += same;
        const double luminance = 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];
        sum += luminance, sum2 += luminance * luminance;
    }
    const double share = double(background) / pixels;
    const double spread = std::sqrt(std::max(0.0, sum2 / pixels - (sum / pixels) * (sum / pixels)));
    std::printf("screenshot %dx%d: %.2f%% clear colour, luminance spread %.1f\n", image->width, image->height, 100.0 * share, spread);
    EXPECT_LT(share, 0.01) << "the terrain does not fill the view";
    EXPECT_GT(spread, 5.0) << "a uniform picture is no shaded terrain";
}
