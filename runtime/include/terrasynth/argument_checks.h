// terrasynth/argument_checks.h: the ranges of the numbers more than one front end takes (the
// terrasynth CLI's flags, terrasynth_editor's and terrasynth_game's, the Python module's
// arguments), and the check that refuses the others, so a number means the same and is refused the
// same way everywhere. Command lines apply the rule through the CLI11 validator of runtime/flags
// (terrasynth_flags/flag_checks.h: flags::FiniteRange(ranges::kSeed)), the Python module through
// checkArgument. The runtime's calls still check what they are given (options, windows, fields);
// these checks come first, so a front end refuses a NaN or a count out of range with the
// argument's name before any work.
#pragma once

#include <string>

#include "terrasynth/checked_number.h"
#include "terrasynth/limits.h"
#include "terrasynth/status.h"

namespace terrasynth {

struct NumberRange {
    double lo = 0.0, hi = 0.0;
};

namespace ranges {
constexpr NumberRange kSeed{0, 4294967295.0};    // SynthesisParams::seed (32 bits)
constexpr NumberRange kOutputLevel{0, 12};       // pyramid level of an output; 0 = full resolution
// Each number of a region X,Y,W,H: 2^31, so x + width never overflows; the command then checks the
// region against the grid's own limits (limits.h, docs/limits.md).
constexpr NumberRange kRegionNumber{-2147483648.0, 2147483648.0};
// A window of the global grid (grid.h) as synthesis takes it: sides and origin (limits.h).
constexpr NumberRange kWindowSide{1, limits::kMaxWindowSide};
constexpr NumberRange kWindowOrigin{-static_cast<double>(limits::kMaxWindowOrigin),
                                    static_cast<double>(limits::kMaxWindowOrigin)};
constexpr NumberRange kGltfTileQuads{1, 4096};   // GltfExportOptions::tile_size
constexpr NumberRange kGltfLods{1, 8};           // GltfExportOptions::lods
constexpr NumberRange kTextureSize{0, 8192};     // GltfExportOptions::texture_size; 0 = none
constexpr NumberRange kMaskBlur{0, 64};          // splat mask blur radius, pixels
constexpr NumberRange kDatabaseLevels{1, 12};    // DatabaseBuildOptions::levels
constexpr NumberRange kDatabaseSpacing{0, 1e5};  // DatabaseBuildOptions::meters_per_pixel; 0 = coarsest input's
constexpr NumberRange kThreads{0, 1024};         // worker threads; 0 = all cores
}  // namespace ranges

// `value` as a finite number in `range`; the error names the argument the way the command-line
// validator does: "seed: expected a finite number in [0, 4294967295], got nan". Thread-safe.
Status checkArgument(const std::string& name, double value, NumberRange range);

}  // namespace terrasynth
