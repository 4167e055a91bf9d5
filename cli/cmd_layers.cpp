// `terrasynth layers <project.tsyn> [--json] [--apply base.png | --size W,H --mpp M] [-o out.png]
//   [--hillshade hs.png]`: prints a project's layer stack (Bradbury et al. 2014; docs/layers.md) and,
// with -o, applies it without running synthesis: to --apply's heightmap, to an imported-heightmap
// base's own grid, or (fractal/blank base) to a --size grid.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "command_registry.h"
#include "terrasynth_flags/flag_checks.h"
#include "outputs.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/limits.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/layers.h"

namespace terrasynth::cli {
namespace {

const char* kCommand = "layers";

struct LayersArgs {
    std::string project, apply, output, hillshade;
    std::vector<int> size;
    double mpp = 0.0;
    bool json = false;
};

Result<Heightfield> gridFor(const LayersArgs& a, const LayerStack& stack) {
    if (!a.apply.empty()) {
        auto ex = readExemplar(a.apply);
        if (!ex) return ex.status();
        return std::move(ex->field);
    }
    if (stack.base.source == BaseSource::Heightmap && a.size.empty()) {
        return readBaseHeightmap(stack);  // the imported heightmap's own grid
    }
    if (stack.base.source == BaseSource::Synthesized)
        return Status::error("the stack's base is the synthesized terrain: give it with --apply base.png (or run "
                             "`terrasynth synth`)");
    if (a.size.size() != 2 || !(a.mpp > 0.0))
        return Status::error("a " + std::string(stack.base.source == BaseSource::Fractal ? "fractal" : "blank") +
                             " base needs the grid: --size W,H --mpp M (or --apply base.png)");
    return Heightfield(a.size[0], a.size[1], a.mpp);
}

// The grid options and every file to be written, checked before any work.
Status checkArguments(const LayersArgs& a) {
    if (!a.size.empty() && (a.size.size() != 2 || a.size[0] < 1 || a.size[1] < 1 || a.size[0] > limits::kMaxWindowSide ||
                            a.size[1] > limits::kMaxWindowSide))
        return Status::error("--size: W,H must be 1.." + std::to_string(limits::kMaxWindowSide) + " each");
    if (a.mpp != 0.0 && !(a.mpp > 0.0 && a.mpp <= 1e5)) return Status::error("--mpp: must be in (0, 100000]");
    std::vector<PlannedOutput> planned;
    if (!a.output.empty()) {
        if (Status s = checkHeightfieldPath(a.output); !s) return s.withContext("-o");
        planned.push_back({"-o", a.output});
        if (!hasSuffix(a.output, ".exr")) planned.push_back({"-o (its sidecar)", sidecarOf(a.output)});
    }
    if (!a.hillshade.empty()) {
        if (!hasSuffix(a.hillshade, ".png")) return Status::error("--hillshade: " + a.hillshade + ": must end in .png");
        planned.push_back({"--hillshade", a.hillshade});
    }
    return checkOutputs(planned);
}

void runLayers(const LayersArgs& a) {
    if (Status s = checkArguments(a); !s) return fail(kCommand, s.message());
    auto stack = readLayerStack(a.project);
    if (!stack) return fail(kCommand, stack.message());
    if (a.json) std::printf("%s\n", jsonText(nlohmann::json::parse(layerStackToJson(*stack)), 2).c_str());
    else std::printf("%s", describeLayerStack(*stack).c_str());
    if (a.output.empty() && a.hillshade.empty()) return;
    auto grid = gridFor(a, *stack);
    if (!grid) return fail(kCommand, grid.message());
    auto out = applyLayerStack(*stack, *grid);
    if (!out) return fail(kCommand, out.message());
    // The heightmap and the hillshade change together or not at all.
    FileTransaction transaction;
    if (!a.hillshade.empty())
        if (Status s = stageHillshadePng(transaction, a.hillshade, *out); !s) return fail(kCommand, s.message());
    if (!a.output.empty())
        if (Status s = stageHeightfield(transaction, a.output, *out); !s) return fail(kCommand, s.message());
    if (Status s = transaction.commit(); !s) return fail(kCommand, s.message());
    if (!a.output.empty()) {
        const HeightRange r = heightRange(*out);
        std::printf("wrote %s: %dx%d, heights %.1f..%.1f m\n", a.output.c_str(), out->width, out->height, r.min, r.max);
    }
    if (!a.hillshade.empty()) std::printf("wrote %s\n", a.hillshade.c_str());
}

void addLayersCommand(CLI::App& app) {
    auto args = std::make_shared<LayersArgs>();
    auto* cmd = app.add_subcommand(kCommand, "Print (and optionally apply) a project's frequency-band layer stack");
    cmd->add_option("project", args->project, "Project file (.tsyn) or a JSON array of layers")->required();
    cmd->add_flag("--json", args->json, "Print the normalised JSON instead of the summary");
    cmd->add_option("--apply", args->apply, "Heightmap to use as the base/grid (any format readExemplar reads)");
    cmd->add_option("--size", args->size, "Grid W,H for a fractal or blank base")
        ->delimiter(',')
        ->expected(2)
        ->check(flags::FiniteRange(1, limits::kMaxWindowSide));
    cmd->add_option("--mpp", args->mpp, "Grid spacing in metres per pixel (with --size)")->check(flags::FiniteRange(1e-6, 1e5));
    cmd->add_option("-o,--output", args->output, "Write the composed heightmap (.png, .f32, .exr)");
    cmd->add_option("--hillshade", args->hillshade, "Write a hillshade PNG of the composed terrain");
    setAction(cmd, [args] { runLayers(*args); });
}

const CommandRegistration kReg{kCommand, 35, addLayersCommand};

}  // namespace
}  // namespace terrasynth::cli
