// The AVX2 steps of core/block_bounds.h's BlockRowBounds (the AVX-512 table uses them too).
// Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

namespace shadowlab::block_bounds_avx2 {

// Component of lane k of the segment's vector j (and j + 3): (8j + k) mod 3.
[[gnu::always_inline]] inline int lane_component(int j, int k) { return (8 * j + k) % 3; }

bool add_full_segment(const float* f, float* lanes) {
  __m256 lo[3], hi[3];
  __m256 nan = _mm256_setzero_ps();
  for (int j = 0; j < 3; ++j) {
    lo[j] = _mm256_loadu_ps(lanes + 8 * j);
    hi[j] = _mm256_loadu_ps(lanes + 24 + 8 * j);
  }
  for (int v = 0; v < 6; ++v) {
    const __m256 p = _mm256_loadu_ps(f + 8 * v);
    const int j = v % 3;
    nan = _mm256_or_ps(nan, _mm256_cmp_ps(p, p, _CMP_UNORD_Q));
    lo[j] = _mm256_min_ps(p, lo[j]);  // p < lo ? p : lo (the scalar path's form)
    hi[j] = _mm256_max_ps(p, hi[j]);  // p > hi ? p : hi
  }
  for (int j = 0; j < 3; ++j) {
    _mm256_storeu_ps(lanes + 8 * j, lo[j]);
    _mm256_storeu_ps(lanes + 24 + 8 * j, hi[j]);
  }
  return _mm256_movemask_ps(nan) != 0;
}

// Minimum (or maximum) over the lanes of v whose component is c, with the other lanes set to
// `fill` (+inf for a minimum, −inf for a maximum).
template <bool kMax>
[[gnu::always_inline]] inline float fold_component(const float* v, int c, float fill) {
  __m256 m = _mm256_set1_ps(fill);
  for (int j = 0; j < 3; ++j) {
    alignas(32) int32_t sel[8];
    for (int k = 0; k < 8; ++k) sel[k] = lane_component(j, k) == c ? -1 : 0;
    const __m256 x = _mm256_blendv_ps(
        _mm256_set1_ps(fill), _mm256_loadu_ps(v + 8 * j),
        _mm256_castsi256_ps(_mm256_load_si256(reinterpret_cast<const __m256i*>(sel))));
    m = kMax ? _mm256_max_ps(x, m) : _mm256_min_ps(x, m);
  }
  __m256 s = _mm256_permute2f128_ps(m, m, 1);
  m = kMax ? _mm256_max_ps(s, m) : _mm256_min_ps(s, m);
  s = _mm256_shuffle_ps(m, m, 0x4E);
  m = kMax ? _mm256_max_ps(s, m) : _mm256_min_ps(s, m);
  s = _mm256_shuffle_ps(m, m, 0xB1);
  m = kMax ? _mm256_max_ps(s, m) : _mm256_min_ps(s, m);
  return _mm256_cvtss_f32(m);
}

float fold_min(const float* v, int c) { return fold_component<false>(v, c, __builtin_inff()); }
float fold_max(const float* v, int c) { return fold_component<true>(v, c, -__builtin_inff()); }

}  // namespace shadowlab::block_bounds_avx2
#endif
