// Integer hashing shared by the synthesis kernels and mirrored bit-for-bit in
// runtime/src/synth/hash.h. Pure functions of global coordinates and the seed: this is what makes a
// window of the terrain independent of the window it was computed in (windowed determinism).

// 32-bit avalanche hash (lowbias32, Chris Wellons).
uint ts_hash_u32(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

uint ts_hash3(int x, int y, uint salt) {
    return ts_hash_u32((uint)x ^ ts_hash_u32((uint)y ^ ts_hash_u32(salt)));
}

// Uniform in [-1, 1], exactly representable steps of 2^-23.
float ts_hash_signed(uint h) {
    return (float)(h >> 8) * (2.0f / 16777215.0f) - 1.0f;
}

// Salt for one use of randomness at one level: purpose 0 = initialisation, 1/2 = jitter x/y.
uint ts_level_salt(uint seed, int level, uint purpose) {
    return ts_hash_u32(seed ^ ts_hash_u32((uint)level * 16u + purpose));
}
