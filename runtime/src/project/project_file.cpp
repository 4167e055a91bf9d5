// The .tsyn project file (docs/project-format.md). Unknown keys are rejected so a typo never
// silently falls back to a default; sections owned by other modules are kept verbatim.
#include <sys/stat.h>

#include <cmath>

#include "core/sidecar.h"
#include "terrasynth/heightfield_io.h"
#include "terrasynth/project.h"

namespace terrasynth {
namespace {

using nlohmann::json;

std::string folderOf(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::string resolve(const std::string& base_dir, const std::string& path) {
    if (path.empty() || path[0] == '/') return path;
    return base_dir + "/" + path;
}

// Reads typed fields and remembers the first error, prefixed with the file and field path.
class FieldReader {
public:
    FieldReader(const std::string& file) : file_(file) {}
    bool ok() const { return status_.isOk(); }
    Status status() const { return status_; }
    void fail(const std::string& field, const std::string& problem) { fail(field + ": " + problem); }
    void fail(const std::string& message) {
        if (status_.isOk()) status_ = Status::error(file_ + ": " + message);
    }
    template <class T>
    void number(const json& object, const char* key, const std::string& path, T* out, double lo, double hi) {
        auto v = detail::readNumberInRange(object, key, path, lo, hi);
        if (!v) return fail(v.message());
        if (!v.value()) return;
        if (std::is_integral_v<T> && *v.value() != std::floor(*v.value())) return fail(path, "must be a whole number");
        *out = static_cast<T>(*v.value());
    }
    void knownKeys(const json& object, const std::string& path, std::initializer_list<const char*> keys) {
        for (auto it = object.begin(); it != object.end(); ++it) {
            bool known = false;
            for (const char* k : keys) known = known || it.key() == k;
            if (!known) fail(path.empty() ? it.key() : path + "." + it.key(), "unknown field");
        }
    }

private:
    std::string file_;
    Status status_ = Status::ok();
};

}  // namespace

std::string Project::databaseCachePath() const {
    if (!database.empty()) return database;
    const std::string stem = path.empty() ? std::string("terrain") : path.substr(0, path.find_last_of('.'));
    return stem + ".tsdb";
}

Result<Project> parseProject(const std::string& text, const std::string& file, const std::string& base_dir) {
    json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return Status::error(file + ": malformed JSON");
    if (!j.is_object()) return Status::error(file + ": expected a JSON object");
    FieldReader r(file);
    r.knownKeys(j, "", {"format", "version", "exemplars", "database", "database_levels", "meters_per_pixel", "size",
                        "origin", "synthesis", "constraints", "layers"});
    Project p;
    p.path = file;
    auto format = j.find("format");
    if (format != j.end() && *format != "terrasynth-project") r.fail("format", "must be \"terrasynth-project\"");
    int version = Project::kFormatVersion;
    r.number(j, "version", "version", &version, 1, 1e9);
    if (version > Project::kFormatVersion)
        r.fail("version", "project version " + std::to_string(version) + " is newer than this build reads (" +
                              std::to_string(Project::kFormatVersion) + ")");
    if (auto ex = j.find("exemplars"); ex != j.end()) {
        if (!ex->is_array() || ex->empty()) {
            r.fail("exemplars", "must be a non-empty array of file or folder paths");
        } else {
            for (size_t i = 0; i < ex->size(); ++i) {
                if (!(*ex)[i].is_string()) r.fail("exemplars[" + std::to_string(i) + "]", "must be a path");
                else p.exemplars.push_back(resolve(base_dir, (*ex)[i].get<std::string>()));
            }
        }
    }
    if (auto db = j.find("database"); db != j.end()) {
        if (!db->is_string()) r.fail("database", "must be a path");
        else p.database = resolve(base_dir, db->get<std::string>());
    }
    if (p.exemplars.empty() && p.database.empty()) r.fail("exemplars", "give \"exemplars\" or \"database\"");
    r.number(j, "database_levels", "database_levels", &p.database_levels, 1, 12);
    r.number(j, "meters_per_pixel", "meters_per_pixel", &p.meters_per_pixel, 0, 1e5);
    for (const char* key : {"size", "origin"}) {
        auto it = j.find(key);
        if (it == j.end()) continue;
        if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number_integer() || !(*it)[1].is_number_integer()) {
            r.fail(key, "must be [x, y] whole numbers");
            continue;
        }
        const int64_t a = (*it)[0].get<int64_t>(), b = (*it)[1].get<int64_t>();
        if (key[0] == 's') {
            if (a < 1 || b < 1 || a > 16384 || b > 16384) r.fail("size", "each side must be 1..16384");
            p.width = static_cast<int>(a), p.height = static_cast<int>(b);
        } else {
            if (std::llabs(a) > (1 << 28) || std::llabs(b) > (1 << 28)) r.fail("origin", "must be within +-2^28");
            p.origin_x = a, p.origin_y = b;
        }
    }
    if (auto s = j.find("synthesis"); s != j.end()) {
        if (!s->is_object()) {
            r.fail("synthesis", "must be an object");
        } else {
            r.knownKeys(*s, "synthesis", {"seed", "jitter", "correction_passes", "coarsest_level", "first_constrained_level",
                                          "hold_point_heights", "drainage"});
            r.number(*s, "seed", "synthesis.seed", &p.synthesis.seed, 0, 4294967295.0);
            r.number(*s, "jitter", "synthesis.jitter", &p.synthesis.jitter, 0, 1);
            r.number(*s, "correction_passes", "synthesis.correction_passes", &p.synthesis.correction_passes, 0, 4);
            r.number(*s, "coarsest_level", "synthesis.coarsest_level", &p.synthesis.coarsest_level, -1, 12);
            r.number(*s, "first_constrained_level", "synthesis.first_constrained_level",
                     &p.synthesis.first_constrained_level, 0, 12);
            if (auto d = s->find("drainage"); d != s->end()) {  // issue 17: "off" | "breach"
                if (*d == "off") p.synthesis.drainage = Drainage::Off;
                else if (*d == "breach") p.synthesis.drainage = Drainage::Breach;
                else r.fail("synthesis.drainage", "must be \"off\" or \"breach\"");
            }
            if (auto hold = s->find("hold_point_heights"); hold != s->end()) {
                if (!hold->is_boolean()) r.fail("synthesis.hold_point_heights", "must be true or false");
                else p.hold_point_heights = hold->get<bool>();
            }
        }
    }
    if (auto c = j.find("constraints"); c != j.end()) {
        if (!c->is_object()) r.fail("constraints", "must be an object");
        else p.constraints = *c;
    }
    if (auto l = j.find("layers"); l != j.end()) {
        if (!l->is_array()) r.fail("layers", "must be an array");
        else p.layers = *l;
    }
    if (!r.ok()) return r.status();
    return p;
}

Result<Project> loadProject(const std::string& path) {
    auto bytes = readFileBytes(path);
    if (!bytes) return bytes.status();
    return parseProject(bytes.value(), path, folderOf(path));
}

std::string projectToJson(const Project& p) {
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
          {"hold_point_heights", p.hold_point_heights}}},
        {"constraints", p.constraints},
        {"layers", p.layers},
    };
    if (!p.exemplars.empty()) j["exemplars"] = p.exemplars;
    if (!p.database.empty()) j["database"] = p.database;
    return j.dump(2) + "\n";
}

Status saveProject(const Project& project, const std::string& path) {
    return writeFileAtomically(path, projectToJson(project));
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
