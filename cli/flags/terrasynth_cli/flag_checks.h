// terrasynth_cli/flag_checks.h: the CLI11 validator every numeric flag of terrasynth,
// terrasynth_editor and terrasynth_game uses (instead of CLI::Range, which NaN passes): a finite
// number in [lo, hi], by terrasynth::parseFiniteNumber, the check the plugin's option string uses.
// A refused value is CLI11's ValidationError: "--flag: expected a finite number in [lo, hi], got 'nan'".
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "terrasynth/checked_number.h"

namespace terrasynth::cli {

// Bound of each number of a --region X,Y,W,H list: 2^31, so x + width never overflows; the command
// then checks the region against the grid's own limits (docs/limits.md).
constexpr double kMaxRegionNumber = 2147483648.0;

// For flags that take several values (a delimited list), each value is checked.
inline CLI::Validator FiniteRange(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            auto parsed = parseFiniteNumber(text, lo, hi);
            return parsed ? std::string() : parsed.message();
        },
        finiteRangeText(lo, hi), "FINITE_RANGE");
}

}  // namespace terrasynth::cli
