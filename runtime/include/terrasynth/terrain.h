// terrasynth/terrain.h: a project made ready to answer height queries, for the plugin, the exporter
// and the CLI: a read-only view of the world an EditSession (edit_session.h) would show, without
// the edits' machinery. It owns the database and the synthesizers.
//
// The extent's heights come from the project's edited-heights sidecar when it names one whose digest
// matches (what the designer saw), else from synthesizing the project afresh; the world around it
// and its coarser levels are defined as in edit_session.h.
//
// Threading: every method is thread-safe. Each calling thread gets its own Synthesizer (created on
// first use), so worker threads synthesize tiles in parallel.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "terrasynth/project.h"

namespace terrasynth {

struct TerrainOptions {
    SynthesizerOptions synthesizer;
    DatabaseBuildOptions database;  // used when the cache must be (re)built
    // Told about recoverable surprises (an edited-heights sidecar that is missing or no longer
    // matches its project: the terrain is then synthesized afresh). Null: kept in warnings() only.
    std::function<void(const std::string&)> on_warning;
};

class Terrain {
public:
    static Result<std::shared_ptr<Terrain>> open(const std::string& project_path, const TerrainOptions& options = {});
    static Result<std::shared_ptr<Terrain>> fromProject(Project project, const TerrainOptions& options = {});
    ~Terrain();

    // The project, with synthesis.constraints set to its parsed constraints (points lifted).
    const Project& project() const;
    const ExemplarDatabase& database() const;
    std::shared_ptr<const ExemplarDatabase> databasePtr() const;
    // Metres per pixel at `level` (database spacing * 2^level).
    double metersPerPixel(int level = 0) const;
    // The project's own extent at level 0.
    PixelWindow extent() const;
    // Whether the extent's heights came from an edited-heights sidecar.
    bool usesEditedHeights() const;
    // Sidecar problems met while opening, oldest first.
    std::vector<std::string> warnings() const;

    // Creates the calling thread's synthesizer now (device context, kernels, database upload)
    // rather than on its first query: worker threads call it before a frame loop starts, so that
    // no OpenCL context or program is made while frames are drawn or a graphics context closes
    // (in one process, a CPU OpenCL driver and a software GL driver may both be compiling with the
    // same LLVM). Errors: those of creating a synthesizer (no OpenCL device, kernel build).
    Status prepareThisThread();

    // Final heights (synthesis + edits) of a window of the global grid at `level`.
    // Bit-identical for overlapping windows.
    Result<Heightfield> heights(const PixelWindow& window, int level = 0);
    // Heights plus the exemplar coordinate map (of the reference synthesis, also inside an edited
    // extent).
    Result<SynthesisOutput> synthesize(const PixelWindow& window, int level = 0, bool want_sources = false);
    // Level-0 height at world point (x east, y north, metres), bilinear between the four samples
    // around it (grid.h); heightsAt for many points.
    Result<double> heightAt(double world_x, double world_y);
    Result<std::vector<double>> heightsAt(const std::vector<std::array<double, 2>>& world_points);

    // Coherent re-synthesis (s5.3) for scripts and the CLI: this project's extent as an edit of
    // `previous` (same database, extent and synthesis settings; freeze brushes and pastes alike),
    // through an EditSession opened on `previous` and given this project's constraints as one
    // setConstraints() edit: only the reach of what changed is re-synthesized Free, a band of
    // IncrementalTerrain::kCoherentBand pixels around it Coherent, and everything beyond keeps the
    // previous heights bit for bit. `changed` (optional) receives the box of what moved, `before`
    // the previous extent's heights.
    Result<Heightfield> heightsAfterEditOf(Terrain& previous, PixelWindow* changed = nullptr,
                                           Heightfield* before = nullptr);

private:
    struct Impl;
    explicit Terrain(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace terrasynth
