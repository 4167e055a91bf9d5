// The game's command line (CLI11) and the checks that run before any window opens.
#include "terrasynth_game/game_options.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <CLI/CLI.hpp>

#include "terrasynth/database.h"
#include "terrasynth/file_transaction.h"
#include "terrasynth/heightfield_io.h"
#include "opencl_check.h"
#include "terrasynth/checked_number.h"
#include "terrasynth_flags/flag_checks.h"
#include "terrasynth_plugin/plugin_options.h"

namespace terrasynth::game {
namespace fs = std::filesystem;

Status parseSize(const std::string& text, int* width, int* height) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
        return Status::error("--size " + text + ": expected WxH, e.g. 1280x720");
    if (w < 160 || h < 120 || w > 8192 || h > 8192)
        return Status::error("--size " + text + ": width in [160, 8192], height in [120, 8192]");
    *width = w;
    *height = h;
    return Status::ok();
}

Status parsePair(const std::string& flag, const std::string& text, double* a, double* b, double bound) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos) return Status::error(flag + " " + text + ": expected X,Y");
    auto x = parseFiniteNumber(text.substr(0, comma), -bound, bound);
    auto y = parseFiniteNumber(text.substr(comma + 1), -bound, bound);
    if (!x || !y) return Status::error(flag + " " + text + ": expected X,Y, each " + finiteRangeText(-bound, bound));
    *a = *x;
    *b = *y;
    return Status::ok();
}

std::optional<GameOptions> parseGameOptions(int argc, char** argv, std::optional<int>* exit_code,
                                            const std::string& default_project) {
    GameOptions o;
    o.project_path = default_project;
    CLI::App app{"terrasynth_game: fly over an endless world synthesized from a seed while you fly"};
    std::string start, size = "1280x720", backend = "opencl";
    uint32_t seed = 0;
    auto* seed_opt = app.add_option("--seed", seed, "World seed (default: the project's)")->check(flags::FiniteRange(ranges::kSeed));
    app.add_option("--project", o.project_path, "Project (.tsyn) whose exemplars and settings to use")
        ->capture_default_str();
    auto* start_opt = app.add_option("--start", start, "Start position X,Y in km (x east, y north)");
    app.add_option("--size", size, "Window size WxH")->capture_default_str();
    app.add_option("--backend", backend, "Synthesizer: opencl or reference (plain C++)")
        ->check(CLI::IsMember({"opencl", "reference"}))
        ->capture_default_str();
    app.add_option("--autopilot", o.autopilot_s, "Fly terrain-following for this many seconds, then quit")
        ->check(flags::FiniteRange(0.0, 1e6));
    app.add_option("--fixed-dt", o.fixed_dt_s, "Deterministic steps of this many simulated seconds per frame")
        ->expected(0, 1)
        ->default_str("0.0333")
        ->check(flags::FiniteRange(0.001, 1.0));
    app.add_option("--screenshot-every", o.screenshot_every, "Save a screenshot every N frames (N steps with --fixed-dt: the settled 3D view); needs --out")
        ->check(flags::FiniteRange(1, 1000000));
    app.add_option("--out", o.out_dir, "Folder for screenshots");
    app.add_option("--stats", o.stats_path, "Write frame timings and flight statistics (JSON) at exit");
    app.add_option("--terrain-options", o.terrain_options,
                   "Terrain options as for osgviewer -O, e.g. \"pixelError=12 meshStep=2\"");
    app.add_option("--check-holes", o.check_holes_every, "Count hole pixels every N frames (sky drawn magenta)")
        ->check(flags::FiniteRange(1, 1000000));
    app.add_flag("--replay", o.replay, "After the flight, redraw its camera path with every tile resident");
    app.add_option("--heading", o.heading_deg, "Autopilot course in degrees clockwise from north")
        ->check(flags::FiniteRange(-360.0, 360.0));
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        *exit_code = app.exit(e);
        return std::nullopt;
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        *exit_code = 2;
        return std::nullopt;
    }
    auto fail = [&](const Status& s) {
        std::fprintf(stderr, "terrasynth_game: %s\n", s.message().c_str());
        *exit_code = 2;
        return std::nullopt;
    };
    // --fixed-dt without a value: CLI11 leaves the default string's value.
    if (app.count("--fixed-dt") && o.fixed_dt_s <= 0.0) o.fixed_dt_s = 1.0 / 30.0;
    if (*seed_opt) o.seed = seed;
    if (Status s = parseSize(size, &o.width, &o.height); !s) return fail(s);
    if (*start_opt) {
        if (Status s = parsePair("--start", start, &o.start_x_km, &o.start_y_km, kMaxStartKm); !s) return fail(s);
        o.start_given = true;
    }
    o.backend = backend == "reference" ? SynthesisBackend::Reference : SynthesisBackend::OpenCL;
    if (o.screenshot_every > 0 && o.out_dir.empty()) return fail(Status::error("--screenshot-every needs --out DIR"));
    return o;
}

namespace {

// Writes and removes a probe file: the honest test of "can this process write here".
Status probeWritable(const fs::path& folder, const std::string& what) {
    const fs::path probe = folder / ".terrasynth_game.probe.tmp";
    {
        std::ofstream f(probe);
        if (!f || !(f << "probe") || !f.flush())
            return Status::error(what + ": cannot write in " + folder.string() + " (" + std::strerror(errno) + ")");
    }
    std::error_code ec;
    fs::remove(probe, ec);
    return Status::ok();
}

Status checkOutputs(const GameOptions& o) {
    if (!o.out_dir.empty()) {
        std::error_code ec;
        fs::create_directories(o.out_dir, ec);
        if (ec) return Status::error("--out " + o.out_dir + ": cannot create the folder (" + ec.message() + ")");
        if (!fs::is_directory(o.out_dir)) return Status::error("--out " + o.out_dir + ": not a folder");
        if (Status s = probeWritable(o.out_dir, "--out " + o.out_dir); !s) return s;
    }
    // Written at exit through a FileTransaction, which makes a missing folder: checked as the editor does.
    if (!o.stats_path.empty())
        if (Status s = FileTransaction::checkTarget(o.stats_path); !s) return s.withContext("--stats");
    return Status::ok();
}

// What a database rebuild would read must be readable, and the cache must be writable, before a
// window opens; a fresh cache needs neither.
Status checkDatabaseInputs(const Project& project) {
    if (project.exemplars.empty()) return Status::ok();  // a prebuilt database: Terrain opens it
    DatabaseBuildOptions options;
    options.levels = project.database_levels;
    options.meters_per_pixel = project.meters_per_pixel;
    auto digest = digestInputs(project.exemplars, options);
    if (!digest) return digest.status().withContext(project.path);
    const std::string cache = project.databaseCachePath();
    if (::access(cache.c_str(), F_OK) == 0) {
        auto cached = loadDatabase(cache);
        if (cached && cached.value()->input_digest == digest.value()) return Status::ok();
    }
    for (const std::string& input : project.exemplars) {
        std::vector<std::string> files{input};
        if (fs::is_directory(input)) {
            auto listed = listExemplarFiles(input);
            if (!listed) return listed.status();
            files = *listed;
        }
        for (const std::string& f : files)
            if (auto e = readExemplar(f); !e) return e.status();
    }
    const fs::path folder = fs::path(cache).has_parent_path() ? fs::path(cache).parent_path() : fs::path(".");
    return probeWritable(folder, cache + " (database cache)");
}

}  // namespace

std::string gameTerrainOptions(const GameOptions& o) {
    return "tileSize=64 pixelError=10 viewRadius=200000 cacheMB=384 " + o.terrain_options;
}

Result<Project> checkBeforeWindow(const GameOptions& o) {
    if (Status s = checkOutputs(o); !s) return s;
    if (auto terrain = plugin::parsePluginOptions(gameTerrainOptions(o)); !terrain)
        return terrain.status().withContext("--terrain-options");
    auto project = loadProject(o.project_path);
    if (!project) return project.status();
    if (o.seed) project->synthesis.seed = *o.seed;
    if (Status s = checkDatabaseInputs(*project); !s) return s;
    if (o.backend == SynthesisBackend::OpenCL) {
        if (Status s = checkOpenClDevice(); !s)
            return Status::error(s.message() + "; run with --backend reference to synthesize on the CPU in C++");
    }
    return project;
}

}  // namespace terrasynth::game
