// Private: numbers as they appear in messages.
#pragma once

#include <string>

namespace terrasynth::detail {

// Decimal text of v without trailing zeros ("0.25", "12", "1000000").
inline std::string compactNumber(double v) {
    std::string s = std::to_string(v);
    while (s.find('.') != std::string::npos && (s.back() == '0' || s.back() == '.')) {
        const bool dot = s.back() == '.';
        s.pop_back();
        if (dot) break;
    }
    return s;
}

}  // namespace terrasynth::detail
