#pragma once
// Counter-based random numbers: every value is a pure function of (pixel, sample, seed,
// dimension), so results never depend on thread count or scheduling.
#include <cstdint>

namespace shadowlab {

// 64-bit finaliser (splitmix64); a bijective, well-mixed hash.
inline uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Hash of (pixel, sample, seed, dimension).
inline uint64_t rng_hash(uint64_t pixel, uint64_t sample, uint64_t seed, uint64_t dim = 0) {
  return mix64(mix64(mix64(mix64(seed) ^ pixel) ^ sample) ^ dim);
}

// Uniform float in [0, 1) from the top 24 bits of a hash.
inline float rng_float(uint64_t h) { return float(h >> 40) * (1.0f / 16777216.0f); }

}  // namespace shadowlab
