// Integer hashing shared by the synthesis kernels and mirrored bit-for-bit in
// runtime/src/synth/hash.h. Pure functions of global coordinates and the seed: this is what makes a
// window of the terrain independent of the window it was computed in (windowed determinism).

// Helpers are forced inline: a call inside the work-item loop stops CPU drivers (PoCL) from
// vectorising across work-items.
#ifdef __clang__
#define TS_INLINE static inline __attribute__((always_inline))
#else
#define TS_INLINE static inline
#endif

// 32-bit avalanche hash (lowbias32, Chris Wellons).
TS_INLINE uint ts_hash_u32(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

TS_INLINE uint ts_hash3(int x, int y, uint salt) {
    return ts_hash_u32((uint)x ^ ts_hash_u32((uint)y ^ ts_hash_u32(salt)));
}

// Uniform in [-1, 1], exactly representable steps of 2^-23.
TS_INLINE float ts_hash_signed(uint h) {
    return (float)(h >> 8) * (2.0f / 16777215.0f) - 1.0f;
}

// Salt for one use of randomness at one level: purpose 0 = initialisation, 1/2 = jitter x/y.
TS_INLINE uint ts_level_salt(uint seed, int level, uint purpose) {
    return ts_hash_u32(seed ^ ts_hash_u32((uint)level * 16u + purpose));
}
