// Issue 20, both backends: when every candidate of a pixel is rejected (a painted type that no
// exemplar pixel has, so no seed either) the correction kernel keeps the pixel's own coordinate
// instead of indexing with -1, identically in OpenCL and in the C++ reference. The database and
// project written here are also what scripts/valgrind_databases.sh runs both backends on.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "terrasynth/synthesizer.h"
#include "test_support.h"

using namespace terrasynth;

namespace {

// The default database with one more terrain type that no pixel has.
std::shared_ptr<const ExemplarDatabase> databaseWithAnEmptyType() {
    auto db = std::make_shared<ExemplarDatabase>(*test::defaultDatabase());
    db->type_names.push_back("phantom");
    return db;
}

Result<SynthesisOutput> synthesizePainted(const std::shared_ptr<const ExemplarDatabase>& db, SynthesisBackend backend) {
    SynthesizerOptions options;
    options.backend = backend;
    auto synthesizer = Synthesizer::create(db, options);
    if (!synthesizer) return synthesizer.status();
    auto constraints = std::make_shared<SynthesisConstraints>();
    TypePaint& paint = constraints->types;
    paint.x = -200, paint.y = -200, paint.width = paint.height = 600;
    paint.types.assign(600 * 600, TypePaint::kUnpainted);
    for (int y = 150; y < 400; ++y)
        for (int x = 150; x < 400; ++x) paint.types[y * 600 + x] = static_cast<uint8_t>(db->type_names.size() - 1);
    SynthesisParams params;
    params.seed = 3;
    params.constraints = constraints;
    return (*synthesizer)->synthesize(PixelWindow{-40, -30, 160, 120}, params, 0, /*want_sources=*/true);
}

TEST(ClHardening, RejectedCandidatesEverywhereKeepThePixelsCoordinate) {
    const auto db = databaseWithAnEmptyType();
    auto ref = synthesizePainted(db, SynthesisBackend::Reference);
    auto cl = synthesizePainted(db, SynthesisBackend::OpenCL);
    ASSERT_TRUE(ref) << ref.message();
    ASSERT_TRUE(cl) << cl.message();
    for (float h : ref->heights.heights) ASSERT_TRUE(std::isfinite(h) && std::fabs(h) < 2e4f);
    const DatabaseLevel& l0 = db->levels[0];
    for (size_t i = 0; i < ref->source_x.size(); ++i) {
        const AtlasRect& r = l0.rects[ref->source_exemplar[i]];
        ASSERT_GE(ref->source_x[i], 0.0f);
        ASSERT_LE(ref->source_x[i], r.width - 1.0f);
    }
    // Same tolerance as the differential tests: at most 1 pixel in 1000 off by more than 1 mm.
    size_t off = 0;
    for (size_t i = 0; i < cl->heights.size(); ++i) off += std::fabs(cl->heights.heights[i] - ref->heights.heights[i]) > 1e-3f;
    EXPECT_LE(off, cl->heights.size() / 1000) << off << " pixels differ";

    // Files for scripts/valgrind_databases.sh: the database and a project painting the empty type.
    const std::string dir = test::scratchDir("cl_hardening_files");
    ASSERT_TRUE(saveDatabase(*db, dir + "/phantom.tsdb"));
    const nlohmann::json project = {
        {"format", "terrasynth-project"}, {"database", "phantom.tsdb"}, {"size", {96, 80}},
        {"synthesis", {{"first_constrained_level", 0}}},
        {"constraints", {{"types", {{"strokes", {{{"type", "phantom"}, {"radius_px", 30}, {"points", {{20, 20}, {70, 60}}}}}}}}}}};
    std::ofstream(dir + "/phantom.tsyn") << project.dump(1);
}

}  // namespace
