// The project format's constraints, read and written back (constraintsToJson is the inverse of
// parseConstraints): every example in docs/ and the shipped projects.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "terrasynth/constraints.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/project.h"
#include "test_support.h"

namespace terrasynth {
namespace {

using nlohmann::json;

std::string read(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Every ```json block of a Markdown file that parses and holds a "constraints" object.
std::vector<json> constraintExamples(const std::string& markdown) {
    std::vector<json> out;
    const std::regex block("```json\\n([\\s\\S]*?)```");
    for (auto it = std::sregex_iterator(markdown.begin(), markdown.end(), block); it != std::sregex_iterator(); ++it) {
        const json j = json::parse((*it)[1].str(), nullptr, false);
        if (j.is_object() && j.contains("constraints")) out.push_back(j["constraints"]);
    }
    return out;
}

// The masks an example names, made up (8-bit, the extent's size) so the example can be read.
void writeNamedMasks(const json& constraints, const std::string& dir, int w, int h) {
    for (const char* section : {"types", "freeze"}) {
        if (!constraints.contains(section) || !constraints[section].contains("mask")) continue;
        std::vector<uint8_t> pixels(static_cast<size_t>(w) * h, 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) pixels[static_cast<size_t>(y) * w + x] = static_cast<uint8_t>((x / 64 + y / 64) % 3);
        ASSERT_TRUE(writePng8(dir + "/" + constraints[section]["mask"].get<std::string>(), w, h, 1, pixels));
    }
}

void expectSame(const SynthesisConstraints& a, const SynthesisConstraints& b) {
    ASSERT_EQ(a.points.size(), b.points.size());
    for (size_t i = 0; i < a.points.size(); ++i) EXPECT_TRUE(a.points[i].samePlacement(b.points[i])) << "points[" << i << "]";
    ASSERT_EQ(a.curves.size(), b.curves.size());
    for (size_t i = 0; i < a.curves.size(); ++i) {
        EXPECT_EQ(a.curves[i].course, b.curves[i].course);
        EXPECT_EQ(a.curves[i].spline, b.curves[i].spline);
        ASSERT_EQ(a.curves[i].widgets.size(), b.curves[i].widgets.size());
        for (size_t k = 0; k < a.curves[i].widgets.size(); ++k) {
            const CurveWidget &u = a.curves[i].widgets[k], &v = b.curves[i].widgets[k];
            EXPECT_TRUE(u.t == v.t && u.height_m == v.height_m && u.left_gradient == v.left_gradient &&
                        u.right_gradient == v.right_gradient && u.left_reach_px == v.left_reach_px &&
                        u.right_reach_px == v.right_reach_px);
        }
    }
    EXPECT_EQ(a.types.types, b.types.types);
    EXPECT_EQ(a.types.x, b.types.x);
    EXPECT_EQ(a.freeze.types, b.freeze.types);
    ASSERT_EQ(a.pastes.size(), b.pastes.size());
    for (size_t i = 0; i < a.pastes.size(); ++i) {
        EXPECT_EQ(a.pastes[i].source, b.pastes[i].source);
        EXPECT_EQ(a.pastes[i].exemplar, b.pastes[i].exemplar);
        EXPECT_EQ(a.pastes[i].dx, b.pastes[i].dx);
        EXPECT_EQ(a.pastes[i].dy, b.pastes[i].dy);
        EXPECT_EQ(a.pastes[i].height_offset_m, b.pastes[i].height_offset_m);
    }
}

TEST(ProjectFormat, ConstraintsInEveryDocsExampleRoundTrip) {
    auto db = test::defaultDatabase();
    ASSERT_TRUE(db);
    int examples = 0;
    for (const char* doc : {"project-format.md", "curves.md", "layers.md", "plugin.md", "export.md"}) {
        for (const json& example : constraintExamples(read(test::dataDir() + "/../docs/" + doc))) {
            const std::string dir = test::scratchDir("format_example_" + std::to_string(examples));
            const int w = 1024, h = 1024;
            const int64_t ox = 3000, oy = -2000;  // not at the origin, so offsets are exercised
            writeNamedMasks(example, dir, w, h);
            auto first = parseConstraints(example.dump(), dir, *db, ox, oy, w, h);
            ASSERT_TRUE(first) << doc << ": " << first.message();
            auto written = constraintsToJson(*first, *db, ox, oy, w, h, dir + "/written");
            ASSERT_TRUE(written) << written.message();
            for (const auto& mask : written->masks) ASSERT_TRUE(writePng8(mask.file, mask.width, mask.height, 1, mask.pixels));
            auto second = parseConstraints(written->json, dir, *db, ox, oy, w, h);
            ASSERT_TRUE(second) << doc << ": " << second.message() << "\n" << written->json;
            expectSame(*first, *second);
            // Writing again gives the same text and masks: the written form is a fixed point.
            auto again = constraintsToJson(*second, *db, ox, oy, w, h, dir + "/written");
            ASSERT_TRUE(again);
            EXPECT_EQ(again->json, written->json);
            ASSERT_EQ(again->masks.size(), written->masks.size());
            for (size_t i = 0; i < again->masks.size(); ++i) EXPECT_EQ(again->masks[i].pixels, written->masks[i].pixels);
            ++examples;
        }
    }
    EXPECT_GE(examples, 1);
}

TEST(ProjectFormat, SavedProjectsReadBackTheSame) {
    auto loaded = loadProject(test::dataDir() + "/default.tsyn");
    ASSERT_TRUE(loaded) << loaded.message();
    const std::string dir = test::scratchDir("format_save");
    ASSERT_TRUE(saveProject(*loaded, dir + "/copy.tsyn"));
    auto copy = loadProject(dir + "/copy.tsyn");
    ASSERT_TRUE(copy) << copy.message();
    EXPECT_EQ(copy->exemplars, loaded->exemplars);  // written absolute (outside the folder), read back the same
    EXPECT_EQ(copy->constraints_json, loaded->constraints_json);
    EXPECT_EQ(copy->layers_json, loaded->layers_json);
    EXPECT_EQ(copy->synthesis.seed, loaded->synthesis.seed);
    Project bad = *loaded;
    bad.constraints_json = "{not json";
    Status s = saveProject(bad, dir + "/bad.tsyn");
    EXPECT_FALSE(s);
    EXPECT_NE(s.message().find("constraints"), std::string::npos) << s.message();
}

TEST(ProjectFormat, DrainageIsBreachUnlessTheProjectSaysOff) {
    // Every front end reads its synthesis settings from a project: one that names no drainage
    // breaches (SynthesisParams' default), "off" switches it off, and a save keeps the choice.
    auto parse = [](const std::string& synthesis) {
        return parseProject("{\"database\": \"x.tsdb\", \"synthesis\": {" + synthesis + "}}", "d.tsyn", ".");
    };
    auto unnamed = parse("\"seed\": 3"), off = parse("\"drainage\": \"off\""), breach = parse("\"drainage\": \"breach\"");
    ASSERT_TRUE(unnamed && off && breach);
    EXPECT_EQ(unnamed->synthesis.drainage, Drainage::Breach);
    EXPECT_EQ(off->synthesis.drainage, Drainage::Off);
    EXPECT_EQ(breach->synthesis.drainage, Drainage::Breach);
    auto bad = parse("\"drainage\": \"fill\"");
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.message().find("synthesis.drainage"), std::string::npos) << bad.message();
    auto shipped = loadProject(test::dataDir() + "/default.tsyn");
    ASSERT_TRUE(shipped) << shipped.message();
    EXPECT_EQ(shipped->synthesis.drainage, Drainage::Breach);
    const std::string dir = test::scratchDir("format_drainage");
    ASSERT_TRUE(saveProject(*off, dir + "/off.tsyn"));
    auto again = loadProject(dir + "/off.tsyn");
    ASSERT_TRUE(again) << again.message();
    EXPECT_EQ(again->synthesis.drainage, Drainage::Off);
}

}  // namespace
}  // namespace terrasynth
