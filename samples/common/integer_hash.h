// Integer hashing for the samples' procedural data (terrain noise, per-pixel ray rotations): deterministic on
// every platform, no state.
#ifndef OBSCURA_SAMPLES_INTEGER_HASH_H
#define OBSCURA_SAMPLES_INTEGER_HASH_H

#include <cstdint>

namespace obscura::samples {

// A 32-bit finaliser of xorshift-multiply rounds: every input bit moves about half of the output bits.
inline uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

// The top 24 bits of `bits` as a float in [0, 1).
inline float unit_float(uint32_t bits) { return float(bits >> 8) * (1.0f / 16777216.0f); }

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_INTEGER_HASH_H
