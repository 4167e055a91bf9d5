// terrasynth_flags/flag_checks.h: the CLI11 validator every numeric flag of terrasynth,
// terrasynth_editor and terrasynth_game uses (instead of CLI::Range, which NaN passes): a finite
// number in [lo, hi], by terrasynth::parseFiniteNumber, the rule the Python module's arguments
// (terrasynth/argument_checks.h) and the plugin's option string follow too. Header-only; the
// target terrasynth_flag_checks (runtime/CMakeLists.txt) adds CLI11.
// A refused value is CLI11's ValidationError: "--flag: expected a finite number in [lo, hi], got 'nan'".
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "terrasynth/argument_checks.h"
#include "terrasynth/checked_number.h"

namespace terrasynth::flags {

// For flags that take several values (a delimited list), each value is checked.
inline CLI::Validator FiniteRange(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            auto parsed = parseFiniteNumber(text, lo, hi);
            return parsed ? std::string() : parsed.message();
        },
        finiteRangeText(lo, hi), "FINITE_RANGE");
}
// A range every front end shares (terrasynth/argument_checks.h), e.g. FiniteRange(ranges::kSeed).
inline CLI::Validator FiniteRange(NumberRange range) { return FiniteRange(range.lo, range.hi); }

}  // namespace terrasynth::flags
