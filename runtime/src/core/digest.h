// Private: FNV-1a 64, the digest of file contents (edited-heights sidecars, the bake's unit records)
// and its text form. Detects damage, not tampering: files that must not be trusted are also
// validated field by field after the digest matches.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace terrasynth::detail {

constexpr uint64_t kFnv1aOffset = 1469598103934665603ull;

// Chained through `h`: fnv1a(b, nb, fnv1a(a, na)) is the digest of a followed by b.
inline uint64_t fnv1a(const void* data, size_t n, uint64_t h = kFnv1aOffset) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

// 16 lower-case hex digits.
inline std::string digestText(uint64_t v) {
    static const char* digits = "0123456789abcdef";
    std::string text(16, '0');
    for (int i = 15; i >= 0; --i, v >>= 4) text[i] = digits[v & 15];
    return text;
}

// Exactly 16 hex digits (either case), never a partial or signed number; false otherwise.
inline bool parseDigestText(const std::string& text, uint64_t* out) {
    if (text.size() != 16) return false;
    uint64_t v = 0;
    for (char c : text) {
        int d = -1;
        if (c >= '0' && c <= '9') d = c - '0';
        else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
        else if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
        if (d < 0) return false;
        v = v << 4 | static_cast<uint64_t>(d);
    }
    *out = v;
    return true;
}

}  // namespace terrasynth::detail
