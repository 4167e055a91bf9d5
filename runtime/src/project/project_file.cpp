// The .tsyn project file (docs/project-format.md). Unknown keys are rejected so a typo never
// silently falls back to a default; sections owned by other modules are kept verbatim.
#include <sys/stat.h>

#include <cmath>

#include "core/json_reader.h"
#include "core/paths.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"
#include "terrasynth/project.h"

namespace terrasynth {
namespace {

using nlohmann::json;
using detail::JsonReader;

// A section kept as text, back as JSON (null when it is not JSON).
json sectionJson(const std::string& text) {
    auto parsed = detail::parseJson(text, "section");
    return parsed ? std::move(parsed.value()) : json();
}

}  // namespace

std::string Project::databaseCachePath() const {
    if (!database.empty()) return database;
    const std::string stem = path.empty() ? std::string("terrain") : path.substr(0, path.find_last_of('.'));
    return stem + ".tsdb";
}

std::string Project::folder() const { return path.empty() ? std::string(".") : detail::folderOf(path); }

Status checkProjectExtent(const Project& p) {
    if (p.width < 1 || p.height < 1 || p.width > limits::kMaxWindowSide || p.height > limits::kMaxWindowSide)
        return Status::error("size: each side must be 1.." + std::to_string(limits::kMaxWindowSide));
    // Compared without negating: -INT64_MIN does not exist.
    const int64_t limit = limits::kMaxProjectOrigin;
    if (p.origin_x < -limit || p.origin_x > limit || p.origin_y < -limit || p.origin_y > limit)
        return Status::error("origin: must be within +-2^28 (" + std::to_string(limit) + ") pixels");
    return Status::ok();
}

Result<Project> parseProject(const std::string& text, const std::string& file, const std::string& base_dir) {
    auto parsed = detail::parseJson(text, file);
    if (!parsed) return parsed.status();
    const json& j = *parsed;
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
        // 2^64 - 1 reads as a whole number too: take it as out of range, never wrapped.
        const bool huge = (*it)[0].is_number_unsigned() && (*it)[0].get<uint64_t>() > uint64_t(INT64_MAX);
        const bool huge_b = (*it)[1].is_number_unsigned() && (*it)[1].get<uint64_t>() > uint64_t(INT64_MAX);
        const int64_t a = huge ? INT64_MAX : (*it)[0].get<int64_t>(), b = huge_b ? INT64_MAX : (*it)[1].get<int64_t>();
        if (key[0] == 's') {
            if (a < 1 || b < 1 || a > limits::kMaxWindowSide || b > limits::kMaxWindowSide) {
                r.fail("size", "each side must be 1.." + std::to_string(limits::kMaxWindowSide));
                continue;
            }
            p.width = static_cast<int>(a), p.height = static_cast<int>(b);
        } else {
            p.origin_x = a, p.origin_y = b;
            if (Status s = checkProjectExtent(p); !s) r.failWith(s.message());
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
        // Offset relaxation (synthesizer.h), off unless true.
        q.relax_offsets = s.boolean("relax_offsets", q.relax_offsets);
        // "breach" (the default, SynthesisParams) | "off" (docs/realism.md, "Drainage").
        const std::string drainage = s.string("drainage", q.drainage == Drainage::Off ? "off" : "breach");
        if (drainage == "off") q.drainage = Drainage::Off;
        else if (drainage == "breach") q.drainage = Drainage::Breach;
        else s.fail("drainage", "must be \"off\" or \"breach\"");
        r.failWith(s.finish().message());
    }
    if (const json* c = r.child("constraints")) {
        if (!c->is_object()) r.fail("constraints", "must be an object");
        else p.constraints_json = detail::dumpJson(*c);
    }
    p.edited_heights = detail::resolveRelative(base_dir, r.string("edited_heights", ""));
    if (const json* l = r.child("layers")) {
        if (!l->is_array()) r.fail("layers", "must be an array");
        else p.layers_json = detail::dumpJson(*l);
    }
    if (Status s = r.finish(); !s) return s.withContext(file);
    return p;
}

Result<Project> loadProject(const std::string& path) {
    auto bytes = readFileBytes(path, limits::kMaxJsonBytes);
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
          {"drainage", p.synthesis.drainage == Drainage::Off ? "off" : "breach"},
          {"relax_offsets", p.synthesis.relax_offsets},
          {"hold_point_heights", p.hold_point_heights}}},
        {"constraints", sectionJson(p.constraints_json)},
        {"layers", sectionJson(p.layers_json)},
    };
    if (!p.exemplars.empty()) {
        json& list = j["exemplars"] = json::array();
        for (const std::string& e : p.exemplars) list.push_back(written(e));
    }
    if (!p.database.empty()) j["database"] = written(p.database);
    if (!p.edited_heights.empty()) j["edited_heights"] = written(p.edited_heights);
    return detail::dumpJson(j, 2) + "\n";
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
