#pragma once
// The lane helpers the AVX2 lookup kernels share. Only the files compiled for AVX2 include this
// (map_lookup_receivers_avx2.cpp, map_lookup_taps_avx2.cpp; docs/simd.md); everything lives in
// lookup_avx2 so that no AVX2-compiled inline function is shared with baseline code.
#include <immintrin.h>

#include <cstdint>
#include <cstring>

#include "techniques/lookup/map_lookup_avx2.h"

namespace shadowlab::lookup_avx2 {

inline __m256 dot3(__m256 ax, __m256 ay, __m256 az, __m256 bx, __m256 by, __m256 bz) {
  // ((ax·bx + ay·by) + az·bz): glm::dot's order.
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ax, bx), _mm256_mul_ps(ay, by)),
                       _mm256_mul_ps(az, bz));
}
inline __m256 lane(const float* table, __m256i face) {
  return _mm256_permutevar8x32_ps(_mm256_load_ps(table), face);
}
inline __m256i lane_i(const int32_t* table, __m256i face) {
  return _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(table)), face);
}
inline __m256 set(float v) { return _mm256_set1_ps(v); }

// floor_int (map_receiver.h): truncate, step down where the truncation is above g.
inline __m256i floor_i(__m256 g) {
  const __m256i i = _mm256_cvttps_epi32(g);
  const __m256 above = _mm256_cmp_ps(_mm256_cvtepi32_ps(i), g, _CMP_GT_OQ);
  return _mm256_add_epi32(i, _mm256_castps_si256(above));  // + (-1) where above
}

// 8 packed vec3 (x0 y0 z0 x1 … z7) into x, y, z lanes: three loads, two blends and a permute
// per component (cheaper than three 8-lane gathers; the values are the same floats).
inline void load_vec3x8(const float* p, __m256& x, __m256& y, __m256& z) {
  const __m256 a = _mm256_loadu_ps(p), b = _mm256_loadu_ps(p + 8), c = _mm256_loadu_ps(p + 16);
  // Lane k of a/b/c holds component (8·block + k) mod 3 of point (8·block + k) / 3.
  const __m256 tx = _mm256_blend_ps(_mm256_blend_ps(a, b, 0x92), c, 0x24);  // a0 b1 c2 a3 b4 c5 a6 b7
  const __m256 ty = _mm256_blend_ps(_mm256_blend_ps(a, b, 0x24), c, 0x49);  // c0 a1 b2 c3 a4 b5 c6 a7
  const __m256 tz = _mm256_blend_ps(_mm256_blend_ps(a, b, 0x49), c, 0x92);  // b0 c1 a2 b3 c4 a5 b6 c7
  x = _mm256_permutevar8x32_ps(tx, _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5));
  y = _mm256_permutevar8x32_ps(ty, _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6));
  z = _mm256_permutevar8x32_ps(tz, _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7));
}

inline __m256i clamp_i(__m256i v, __m256i lo, __m256i hi) {
  return _mm256_min_epi32(_mm256_max_epi32(v, lo), hi);
}

}  // namespace shadowlab::lookup_avx2
