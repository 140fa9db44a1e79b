// The AVX2 row of the à-trous filter (techniques/rt/atrous.h): 8 pixels per step, the body of
// atrous_simd.inl. Compiled with -mavx2 -mfma (docs/simd.md; -ffp-contract=off keeps every
// multiply and add separate).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "core/exp_log_avx2.h"
#include "techniques/rt/atrous.h"

namespace shadowlab::atrous_avx2 {

using V = __m256;
constexpr int kL = 8;

// All ones in the lanes l with 0 <= x + l < w.
[[gnu::always_inline]] inline __m256i lanes_in(int x, int w) {
  const __m256i l = _mm256_add_epi32(_mm256_set1_epi32(x), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  return _mm256_andnot_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), l),
                             _mm256_cmpgt_epi32(_mm256_set1_epi32(w), l));
}
[[gnu::always_inline]] inline V vset1(float v) { return _mm256_set1_ps(v); }
[[gnu::always_inline]] inline V vmaskload(const float* p, int x, int w) {
  return _mm256_maskload_ps(p, lanes_in(x, w));
}
[[gnu::always_inline]] inline V vmaskload_at(const float* row, int x, int w) {
  const __m256i m = lanes_in(x, w);
  return _mm256_testz_si256(m, m)
             ? _mm256_setzero_ps()
             : _mm256_maskload_ps(reinterpret_cast<const float*>(
                                      reinterpret_cast<uintptr_t>(row) + uintptr_t(intptr_t(x) * 4)),
                                  m);
}
[[gnu::always_inline]] inline void vmaskstore(float* p, int x, int w, V v) {
  _mm256_maskstore_ps(p, lanes_in(x, w), v);
}
[[gnu::always_inline]] inline V vadd(V a, V b) { return _mm256_add_ps(a, b); }
[[gnu::always_inline]] inline V vsub(V a, V b) { return _mm256_sub_ps(a, b); }
[[gnu::always_inline]] inline V vmul(V a, V b) { return _mm256_mul_ps(a, b); }
[[gnu::always_inline]] inline V vdiv(V a, V b) { return _mm256_div_ps(a, b); }
[[gnu::always_inline]] inline V vsqrt(V a) { return _mm256_sqrt_ps(a); }
[[gnu::always_inline]] inline V vabs(V a) {
  return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a);
}
[[gnu::always_inline]] inline V vneg(V a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
// std::max(a, b) per lane: a < b ? b : a.
[[gnu::always_inline]] inline V vmax(V a, V b) {
  return _mm256_blendv_ps(a, b, _mm256_cmp_ps(a, b, _CMP_LT_OQ));
}
[[gnu::always_inline]] inline V vexp(V x) { return exp_log_avx2::exp_f8(x); }
[[gnu::always_inline]] inline V vpositive(V v) {
  return _mm256_and_ps(v, _mm256_cmp_ps(v, _mm256_setzero_ps(), _CMP_GT_OQ));
}
[[gnu::always_inline]] inline V vselect_nonzero(V c, V a, V b) {
  return _mm256_blendv_ps(b, a, _mm256_cmp_ps(c, _mm256_setzero_ps(), _CMP_NEQ_UQ));
}

#include "techniques/rt/atrous_simd.inl"

}  // namespace shadowlab::atrous_avx2
#endif
