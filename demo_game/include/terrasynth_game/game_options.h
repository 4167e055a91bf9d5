// terrasynth_game/game_options.h: the command line of terrasynth_game, checked before any window.
//
//   terrasynth_game [--seed N] [--project FILE] [--start X,Y] [--size WxH] [--backend opencl|reference]
//                   [--autopilot SECONDS] [--fixed-dt [SECONDS]] [--screenshot-every N --out DIR]
//                   [--stats FILE] [--terrain-options "key=value ..."] [--check-holes N] [--replay]
//                   [--heading DEG]
// Everything that can be wrong with the input is found here (bad flags, unreadable project, no
// OpenCL device, unwritable outputs) so the game can say so and exit 2 before opening a window.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "terrasynth/project.h"
#include "terrasynth/status.h"
#include "terrasynth/synthesizer.h"

namespace terrasynth::game {

struct GameOptions {
    std::string project_path;                 // --project (default: data/default.tsyn)
    std::optional<uint32_t> seed;             // --seed: overrides the project's synthesis seed
    double start_x_km = 0.0, start_y_km = 0.0;  // --start X,Y: world km (x east, y north)
    bool start_given = false;                 // else the middle of the project extent
    int width = 1280, height = 720;           // --size WxH
    SynthesisBackend backend = SynthesisBackend::OpenCL;  // --backend
    double autopilot_s = 0.0;                 // --autopilot: fly this long (simulated s), then quit; 0 = off
    double fixed_dt_s = 0.0;                  // --fixed-dt: simulated seconds per frame; 0 = wall clock
    int screenshot_every = 0;                 // --screenshot-every N frames (steps with --fixed-dt; needs --out)
    std::string out_dir;                      // --out
    std::string stats_path;                   // --stats: JSON written at exit
    std::string terrain_options;              // --terrain-options: the plugin's option string
    int check_holes_every = 0;                // --check-holes N: count hole pixels every N frames
    bool replay = false;                      // --replay: after the flight, redraw its camera path settled
    double heading_deg = 75.0;                // --heading: autopilot course, clockwise from north

    bool deterministic() const { return fixed_dt_s > 0.0; }
};

// Parses argv with CLI11. On --help prints the help and returns exit code 0 in `exit_code`; on a bad
// flag prints CLI11's message and returns 2. Otherwise exit_code stays unset.
std::optional<GameOptions> parseGameOptions(int argc, char** argv, std::optional<int>* exit_code,
                                            const std::string& default_project);

// Checks what does not need a window: the outputs are writable (the --out folder is created), the
// project loads (the loader's message names file and field), the exemplars or database it names can
// be read, and an OpenCL device exists for --backend opencl. Returns the loaded project.
Result<Project> checkBeforeWindow(const GameOptions& options);

// The terrain's option string (the plugin's keys, as osgviewer -O takes them): the game's defaults,
// then --terrain-options (later tokens win). The defaults keep an llvmpipe frame in budget and the
// process under 1 GB: tileSize=64 pixelError=10 viewRadius=200000 cacheMB=384.
std::string gameTerrainOptions(const GameOptions& options);

// "WxH" -> (W, H) in [160, 8192]; "X,Y" -> (X, Y), each finite within +-bound. Errors name the flag.
Status parseSize(const std::string& text, int* width, int* height);
Status parsePair(const std::string& flag, const std::string& text, double* x, double* y, double bound);
// --start's bound: 10^5 km each way, inside the grid synthesis serves (+-2^28 pixels) at any
// spacing from 0.4 m up, so the world under the start is one the synthesizer can make.
constexpr double kMaxStartKm = 1e5;

}  // namespace terrasynth::game
