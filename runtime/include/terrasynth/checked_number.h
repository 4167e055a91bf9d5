// terrasynth/checked_number.h: the one check of a number given as text, used by every numeric
// command-line flag of terrasynth, terrasynth_editor and terrasynth_game (through the CLI11
// validator runtime/flags/terrasynth_flags/flag_checks.h) and by the plugin's option string; the
// same rule for numbers given as numbers (the Python module's) is checkArgument, argument_checks.h.
//
// strtod reads "nan", "inf" and "1e999" as numbers, and a range check written as
// `v < lo || v > hi` (CLI11's Range, an option parser's `d < 0`) is false for NaN, so NaN passes
// it; this check refuses every value that is not finite before comparing.
#pragma once

#include <string>

#include "terrasynth/status.h"

namespace terrasynth {

// `text`, whole (leading and trailing spaces allowed), as a finite number in [lo, hi]. Errors:
// "expected a finite number in [lo, hi], got 'text'" (the caller adds the flag or option name).
// Thread-safe; no locale dependence beyond strtod's (the C locale in every terrasynth program).
Result<double> parseFiniteNumber(const std::string& text, double lo, double hi);

// The rule as printed in messages and help: "a finite number in [lo, hi]".
std::string finiteRangeText(double lo, double hi);

}  // namespace terrasynth
