// Fuzz target: the .tsyn project parser and the sections it carries: the project fields
// (parseProject), its constraints against a small database (parseConstraints: points, curves with
// their course and junction limits, type and freeze strokes, pastes) and its layer stack
// (parseLayerStack, then applied to a small grid). Whatever parses must also survive the round
// trips projectToJson and layerStackToJson.
#include <cmath>

#include "fuzz_support.h"
#include "terrasynth/constraints.h"
#include "terrasynth/database.h"
#include "terrasynth/layers.h"
#include "terrasynth/project.h"

using namespace terrasynth;

namespace {

std::shared_ptr<const ExemplarDatabase> database;

// Two small synthetic exemplars of different types: enough for type names and paste sources.
std::shared_ptr<const ExemplarDatabase> smallDatabase() {
    std::vector<Exemplar> exemplars;
    for (int e = 0; e < 2; ++e) {
        Exemplar ex;
        ex.info.name = e == 0 ? "ridges" : "hills";
        ex.info.terrain_class = e == 0 ? "alpine ranges" : "old eroded ridges / hills";
        ex.field = Heightfield(40, 40, 90.0);
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 40; ++x)
                ex.field.at(x, y) = static_cast<float>(800.0 + 300.0 * std::sin(0.3 * x + e) * std::cos(0.2 * y) + 7.0 * x);
        exemplars.push_back(std::move(ex));
    }
    DatabaseBuildOptions options;
    options.levels = 2;
    options.threads = 1;
    auto db = buildDatabase(std::move(exemplars), options);
    if (!db) __builtin_trap();
    return *db;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    database = smallDatabase();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (!database) LLVMFuzzerInitialize(nullptr, nullptr);
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::string dir = fuzz::scratchDir();
    auto project = parseProject(text, dir + "/fuzz.tsyn", dir);
    if (!project) return 0;
    auto again = parseProject(projectToJson(*project), dir + "/again.tsyn", dir);
    if (!again) __builtin_trap();
    // Extents are linear in cost and bounded by the project limits; keep each run quick.
    const int w = std::min(project->width, 96), h = std::min(project->height, 96);
    (void)parseConstraints(project->constraints_json, dir, *database, project->origin_x, project->origin_y, w, h);
    auto stack = parseLayerStack(project->layers_json, dir);
    if (!stack) return 0;
    if (!parseLayerStack(layerStackToJson(*stack), dir)) __builtin_trap();
    (void)applyLayerStack(*stack, Heightfield(24, 20, 30.0, 500.0f));
    return 0;
}
