#include "terrasynth/checked_number.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/number_text.h"
#include "terrasynth/argument_checks.h"

namespace terrasynth {
namespace {

// Whole numbers as integers ("1000000", not "1e+06"), others as compactNumber gives them.
std::string boundText(double v) {
    if (std::fabs(v) < 1e15 && v == std::floor(v)) return std::to_string(static_cast<long long>(v));
    return detail::compactNumber(v);
}

}  // namespace

std::string finiteRangeText(double lo, double hi) {
    return "a finite number in [" + boundText(lo) + ", " + boundText(hi) + "]";
}

Result<double> parseFiniteNumber(const std::string& text, double lo, double hi) {
    const auto refuse = [&] { return Status::error("expected " + finiteRangeText(lo, hi) + ", got '" + text + "'"); };
    const char* begin = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (end == begin || errno == ERANGE) return refuse();
    while (*end == ' ' || *end == '\t') ++end;
    if (*end != '\0' || !std::isfinite(v) || v < lo || v > hi) return refuse();
    return v;
}

Status checkArgument(const std::string& name, double value, NumberRange range) {
    if (std::isfinite(value) && value >= range.lo && value <= range.hi) return Status::ok();
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);
    return Status::error(name + ": expected " + finiteRangeText(range.lo, range.hi) + ", got " + text);
}

}  // namespace terrasynth
