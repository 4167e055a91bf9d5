// terrasynth/terrain.h: a project made ready to answer height queries, for the plugin, the exporter
// and the CLI. It owns the database and the synthesizers and applies the project's edits.
//
// Threading: every method is thread-safe. Each calling thread gets its own Synthesizer (created on
// first use), so worker threads synthesize tiles in parallel.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "terrasynth/project.h"

namespace terrasynth {

struct TerrainOptions {
    SynthesizerOptions synthesizer;
    DatabaseBuildOptions database;  // used when the cache must be (re)built
};

class Terrain {
public:
    static Result<std::shared_ptr<Terrain>> open(const std::string& project_path, const TerrainOptions& options = {});
    static Result<std::shared_ptr<Terrain>> fromProject(Project project, const TerrainOptions& options = {});

    const Project& project() const { return project_; }
    const ExemplarDatabase& database() const { return *db_; }
    std::shared_ptr<const ExemplarDatabase> databasePtr() const { return db_; }
    // Metres per pixel at `level` (database spacing * 2^level).
    double metersPerPixel(int level = 0) const;

    // Final heights (synthesis + edits) of a window of the global grid at `level`.
    // Bit-identical for overlapping windows.
    Result<Heightfield> heights(const PixelWindow& window, int level = 0);
    // Heights plus the exemplar coordinate map.
    Result<SynthesisOutput> synthesize(const PixelWindow& window, int level = 0, bool want_sources = false);
    // Coherent re-synthesis (s5.3) for scripts and the CLI: this project's extent as an edit of
    // `previous`, which must use the same database, extent and synthesis settings. The previous
    // terrain is synthesized with its history, then only the reach of the constraints that changed
    // (IncrementalTerrain::areaAffectedBy; `changed` receives its bounding box, width 0 = none) is
    // re-synthesized Free, a band of IncrementalTerrain::kCoherentBand pixels around the box
    // Coherent, and everything beyond keeps the previous heights bit for bit. `before` (optional)
    // receives the previous extent's heights, as previous.heights() gives them. Freeze brushes of
    // both projects are frozen. Errors: differing settings, pastes or layers in either project.
    Result<Heightfield> heightsAfterEditOf(Terrain& previous, PixelWindow* changed = nullptr,
                                           Heightfield* before = nullptr);
    // The project's own extent at level 0.
    PixelWindow extent() const { return {project_.origin_x, project_.origin_y, project_.width, project_.height}; }

private:
    Terrain(Project project, std::shared_ptr<const ExemplarDatabase> db, TerrainOptions options)
        : project_(std::move(project)), db_(std::move(db)), options_(std::move(options)) {}
    Result<Synthesizer*> synthesizerForThisThread();
    // How freeze, pastes and layers change the synthesized extent (level 0, row-major), computed once.
    bool hasExtentEdit() const;
    Result<Heightfield> shapedExtent(Synthesizer& synthesizer);
    Result<const std::vector<float>*> extentEdit();

    Project project_;
    std::shared_ptr<const ExemplarDatabase> db_;
    TerrainOptions options_;
    std::mutex mutex_;
    std::unordered_map<std::thread::id, std::unique_ptr<Synthesizer>> synthesizers_;
    std::mutex edit_mutex_;
    bool edit_ready_ = false;
    std::vector<float> edit_;    // shaped - plain, per extent pixel
    std::vector<float> shaped_;  // the shaped extent's heights
};

}  // namespace terrasynth
