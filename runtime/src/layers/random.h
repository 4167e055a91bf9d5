// Counter-based randomness: every value is a hash of (seed, coordinates), so results do not depend on
// evaluation order or thread count, and are the same on every platform.
#pragma once

#include <cstdint>

namespace terrasynth::layers {

inline uint64_t mix64(uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
inline uint64_t hash3(uint64_t seed, int64_t a, int64_t b) {
    return mix64(mix64(seed ^ mix64(static_cast<uint64_t>(a))) ^ static_cast<uint64_t>(b) * 0xD6E8FEB86659FD93ull);
}
// Uniform in [0, 1).
inline double unitFromHash(uint64_t h) { return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); }

// Sequential generator for the quilting search (seeded from hash3).
struct Rng {
    uint64_t state;
    explicit Rng(uint64_t seed) : state(mix64(seed)) {}
    uint64_t next() { return state = mix64(state); }
    double unit() { return unitFromHash(next()); }
    int below(int n) { return static_cast<int>(unit() * n); }
};

}  // namespace terrasynth::layers
