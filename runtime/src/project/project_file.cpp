// The .tsyn project file (docs/project-format.md). Unknown keys are rejected so a typo never
// silently falls back to a default; sections owned by other modules are kept verbatim.
#include <sys/stat.h>

#include <cmath>

#include "core/json_reader.h"
#include "core/paths.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/project.h"

namespace terrasynth {
namespace {

using nlohmann::json;
using detail::JsonReader;

}  // namespace

std::string Project::databaseCachePath() const {
    if (!database.empty()) return database;
    const std::string stem = path.empty() ? std::string("terrain") : path.substr(0, path.find_last_of('.'));
    return stem + ".tsdb";
}

std::string Project::folder() const { return path.empty() ? std::string(".") : detail::folderOf(path); }

Result<Project> parseProject(const std::string& text, const std::string& file, const std::string& base_dir) {
    json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return Status::error(file + ": malformed JSON");
    if (!j.is_object()) return Status::error(file + ": expected a JSON object");
    JsonReader r(j, "");
    Project p;
    p.path = file;
    if (r.has("format") && r.string("format", "") != "terrasynth-project") r.fail("format", "must be \"terrasynth-project\"");
    r.use("format");
    const int64_t version = r.integer("version", Project::kFormatVersion, 1, 1000000000);
    if (version > Project::kFormatVersion)
        r.fail("version", "project version " + std::to_string(version) + " is newer than this build reads (" +
                              std::to_string(Project::kFormatVersion) + ")");
    if (const json* ex = r.child("exemplars")) {
        if (!ex->is_array() || ex->empty()) {
            r.fail("exemplars", "must be a non-empty array of file or folder paths");
        } else {
            for (size_t i = 0; i < ex->size(); ++i) {
                if (!(*ex)[i].is_string()) r.fail("exemplars[" + std::to_string(i) + "]", "must be a path");
                else p.exemplars.push_back(detail::resolveRelative(base_dir, (*ex)[i].get<std::string>()));
            }
        }
    }
    p.database = detail::resolveRelative(base_dir, r.string("database", ""));
    if (r.ok() && p.exemplars.empty() && p.database.empty()) r.fail("exemplars", "give \"exemplars\" or \"database\"");
    p.database_levels = static_cast<int>(r.integer("database_levels", p.database_levels, 1, 12));
    p.meters_per_pixel = r.number("meters_per_pixel", 0, 1e5, p.meters_per_pixel);
    for (const char* key : {"size", "origin"}) {
        const json* it = r.child(key);
        if (!it) continue;
        if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number_integer() || !(*it)[1].is_number_integer()) {
            r.fail(key, "must be [x, y] whole numbers");
            continue;
        }
        const int64_t a = (*it)[0].get<int64_t>(), b = (*it)[1].get<int64_t>();
        if (key[0] == 's') {
            if (a < 1 || b < 1 || a > 16384 || b > 16384) r.fail("size", "each side must be 1..16384");
            p.width = static_cast<int>(a), p.height = static_cast<int>(b);
        } else {
            // Compared without negating: -INT64_MIN does not exist.
            const int64_t limit = int64_t(1) << 28;
            if (a < -limit || a > limit || b < -limit || b > limit) r.fail("origin", "must be within +-2^28");
            p.origin_x = a, p.origin_y = b;
        }
    }
    if (const json* synthesis = r.child("synthesis")) {
        JsonReader s(*synthesis, "synthesis");
        SynthesisParams& q = p.synthesis;
        q.seed = static_cast<uint32_t>(s.integer("seed", q.seed, 0, 4294967295ll));
        q.jitter = static_cast<float>(s.number("jitter", 0, 1, q.jitter));
        q.correction_passes = static_cast<int>(s.integer("correction_passes", q.correction_passes, 0, 4));
        q.coarsest_level = static_cast<int>(s.integer("coarsest_level", q.coarsest_level, -1, 12));
        q.first_constrained_level = static_cast<int>(s.integer("first_constrained_level", q.first_constrained_level, 0, 12));
        p.hold_point_heights = s.boolean("hold_point_heights", p.hold_point_heights);
        r.failWith(s.finish().message());
    }
    if (const json* c = r.child("constraints")) {
        if (!c->is_object()) r.fail("constraints", "must be an object");
        else p.constraints_json = c->dump();
    }
    p.edited_heights = detail::resolveRelative(base_dir, r.string("edited_heights", ""));
    if (const json* l = r.child("layers")) {
        if (!l->is_array()) r.fail("layers", "must be an array");
        else p.layers_json = l->dump();
    }
    if (Status s = r.finish(); !s) return s.withContext(file);
    return p;
}

Result<Project> loadProject(const std::string& path) {
    auto bytes = readFileBytes(path);
    if (!bytes) return bytes.status();
    return parseProject(bytes.value(), path, detail::folderOf(path));
}

std::string projectToJson(const Project& p, const std::string& folder) {
    auto written = [&](const std::string& path) { return folder.empty() ? path : detail::pathForFileIn(folder, path); };
    json j = {
        {"format", "terrasynth-project"},
        {"version", Project::kFormatVersion},
        {"database_levels", p.database_levels},
        {"meters_per_pixel", p.meters_per_pixel},
        {"size", {p.width, p.height}},
        {"origin", {p.origin_x, p.origin_y}},
        {"synthesis",
         {{"seed", p.synthesis.seed},
          {"jitter", p.synthesis.jitter},
          {"correction_passes", p.synthesis.correction_passes},
          {"coarsest_level", p.synthesis.coarsest_level},
          {"first_constrained_level", p.synthesis.first_constrained_level},
          {"hold_point_heights", p.hold_point_heights}}},
        {"constraints", json::parse(p.constraints_json, nullptr, false)},
        {"layers", json::parse(p.layers_json, nullptr, false)},
    };
    if (!p.exemplars.empty()) {
        json& list = j["exemplars"] = json::array();
        for (const std::string& e : p.exemplars) list.push_back(written(e));
    }
    if (!p.database.empty()) j["database"] = written(p.database);
    if (!p.edited_heights.empty()) j["edited_heights"] = written(p.edited_heights);
    return j.dump(2) + "\n";
}

Status saveProject(const Project& project, const std::string& path) {
    for (const std::string* text : {&project.constraints_json, &project.layers_json})
        if (json::parse(*text, nullptr, false).is_discarded())
            return Status::error(path + ": the project's " + (text == &project.layers_json ? "layers" : "constraints") +
                                 " are not valid JSON");
    return writeFileAtomically(path, projectToJson(project, detail::folderOf(path)));
}

Result<std::shared_ptr<const ExemplarDatabase>> openProjectDatabase(const Project& project,
                                                                    const DatabaseBuildOptions& build) {
    if (project.exemplars.empty()) {
        auto db = loadDatabase(project.database);
        if (!db) return db.status().withContext(project.path);
        return db;
    }
    DatabaseBuildOptions options = build;
    options.levels = project.database_levels;
    options.meters_per_pixel = project.meters_per_pixel;
    return loadOrBuildDatabase(project.exemplars, options, project.databaseCachePath());
}

}  // namespace terrasynth
