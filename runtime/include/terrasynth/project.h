// terrasynth/project.h: the .tsyn project file (JSON, versioned; docs/project-format.md).
//
// A project names its exemplars (or a prebuilt database), the terrain extent and spacing, the
// synthesis parameters and seed, and the user's edits (constraints, layers). Paths inside a project
// are relative to the project file's folder.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "terrasynth/synthesizer.h"

namespace terrasynth {

struct Project {
    static constexpr int kFormatVersion = 1;
    std::string path;                      // the file it was loaded from ("" when new)
    std::vector<std::string> exemplars;    // exemplar files or folders (absolute after loading)
    std::string database;                  // prebuilt .tsdb; "" = cache beside the project
    int database_levels = 6;               // L
    double meters_per_pixel = 0.0;         // 0 = coarsest exemplar spacing
    int width = 1024, height = 1024;       // terrain extent in pixels (the world itself is unbounded)
    int64_t origin_x = 0, origin_y = 0;    // global pixel of the extent's north-west corner
    SynthesisParams synthesis;
    // synthesis.hold_point_heights: lift point constraints so finished sites land on their heights
    // (liftPointConstraints in synthesizer.h). false = the paper's plain targets.
    bool hold_point_heights = true;
    // Sections owned by other modules, as compact JSON text, kept verbatim so loading and saving
    // never drops them: the "constraints" object (parseConstraints, constraints.h) and the "layers"
    // array (parseLayerStack, layers.h).
    std::string constraints_json = "{}";
    std::string layers_json = "[]";
    // The edited-heights sidecar an edit session saved beside the project ("" = none): what the
    // designer saw, loaded instead of re-synthesizing while its digest matches (edit_session.h).
    std::string edited_heights;

    // Where the database cache lives: `database` if set, else "<project stem>.tsdb" beside it.
    std::string databaseCachePath() const;
    // The folder relative paths inside the project resolve against ("." for a new project).
    std::string folder() const;
    bool hasLayers() const { return layers_json != "[]"; }
};

// Errors name the file and the JSON field, e.g. "world.tsyn: synthesis.jitter: must be in [0, 1]".
Result<Project> loadProject(const std::string& path);
Result<Project> parseProject(const std::string& json_text, const std::string& path_for_messages,
                             const std::string& base_dir);
// The extent limits every project obeys (limits.h): size 1..16384 per side, origin within +-2^28,
// so the extent and its constraints fit the grid synthesis addresses. Terrain::fromProject checks
// them again, so overrides (the command line's --size and --origin) cannot bypass them.
Status checkProjectExtent(const Project& project);
// Atomic: the previous file survives any failure.
Status saveProject(const Project& project, const std::string& path);
// The project's JSON text. With `folder` (where the file will live), paths inside it are written
// relative to it and all others absolute; without, paths are written as they are held.
// Precondition: constraints_json and layers_json are valid JSON (saveProject checks).
std::string projectToJson(const Project& project, const std::string& folder = "");

// Loads the project's database (from `database`, or the cache rebuilt when stale).
Result<std::shared_ptr<const ExemplarDatabase>> openProjectDatabase(const Project& project,
                                                                    const DatabaseBuildOptions& build = {});

}  // namespace terrasynth
