// Private: integer hashing, bit-for-bit the same as kernels/hash.cl (the kernels and the C++
// reference must agree exactly, and hashes of global coordinates are what make windows independent).
#pragma once

#include <cstdint>

namespace terrasynth::core {

inline uint32_t hashU32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

inline uint32_t hash3(int x, int y, uint32_t salt) {
    return hashU32(static_cast<uint32_t>(x) ^ hashU32(static_cast<uint32_t>(y) ^ hashU32(salt)));
}

// Uniform in [-1, 1].
inline float hashSigned(uint32_t h) {
    return static_cast<float>(h >> 8) * (2.0f / 16777215.0f) - 1.0f;
}

}  // namespace terrasynth::synth

namespace terrasynth::core {

// Salt for one use of randomness at one level: purpose 0 = initialisation, 1/2 = jitter x/y.
inline uint32_t levelSalt(uint32_t seed, int level, uint32_t purpose) {
    return hashU32(seed ^ hashU32(static_cast<uint32_t>(level) * 16u + purpose));
}

}  // namespace terrasynth::synth
