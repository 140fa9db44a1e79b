// The AVX-512 row of the à-trous filter (techniques/rt/atrous.h): 16 pixels per step, the body of
// atrous_simd.inl. Compiled with -mavx512f -mavx512vl -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "core/exp_log_avx512.h"
#include "techniques/rt/atrous.h"

namespace shadowlab::atrous_avx512 {

using V = __m512;
constexpr int kL = 16;

// Lanes l with 0 <= x + l < w.
[[gnu::always_inline]] inline __mmask16 lanes_in(int x, int w) {
  const __m512i l = _mm512_add_epi32(_mm512_set1_epi32(x),
                                     _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
  return _mm512_cmpge_epi32_mask(l, _mm512_setzero_si512()) &
         _mm512_cmplt_epi32_mask(l, _mm512_set1_epi32(w));
}
[[gnu::always_inline]] inline V vset1(float v) { return _mm512_set1_ps(v); }
// p[l] for the lanes with x + l in [0, w) (p points at x), else 0.
[[gnu::always_inline]] inline V vmaskload(const float* p, int x, int w) {
  return _mm512_maskz_loadu_ps(lanes_in(x, w), p);
}
// row[x + l] for the lanes with x + l in [0, w), else 0.
[[gnu::always_inline]] inline V vmaskload_at(const float* row, int x, int w) {
  const __mmask16 m = lanes_in(x, w);
  return m ? _mm512_maskz_loadu_ps(m, reinterpret_cast<const float*>(
                                          reinterpret_cast<uintptr_t>(row) + uintptr_t(intptr_t(x) * 4)))
           : _mm512_setzero_ps();
}
[[gnu::always_inline]] inline void vmaskstore(float* p, int x, int w, V v) {
  _mm512_mask_storeu_ps(p, lanes_in(x, w), v);
}
[[gnu::always_inline]] inline V vadd(V a, V b) { return _mm512_add_ps(a, b); }
[[gnu::always_inline]] inline V vsub(V a, V b) { return _mm512_sub_ps(a, b); }
[[gnu::always_inline]] inline V vmul(V a, V b) { return _mm512_mul_ps(a, b); }
[[gnu::always_inline]] inline V vdiv(V a, V b) { return _mm512_div_ps(a, b); }
[[gnu::always_inline]] inline V vsqrt(V a) { return _mm512_sqrt_ps(a); }
[[gnu::always_inline]] inline V vabs(V a) { return _mm512_abs_ps(a); }
[[gnu::always_inline]] inline V vneg(V a) {
  return _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(a), _mm512_set1_epi32(int(0x80000000u))));
}
// std::max(a, b) per lane: a < b ? b : a.
[[gnu::always_inline]] inline V vmax(V a, V b) {
  return _mm512_mask_mov_ps(a, _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ), b);
}
[[gnu::always_inline]] inline V vexp(V x) { return exp_log_avx512::exp_f16(x); }
[[gnu::always_inline]] inline V vpositive(V v) {
  return _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(v, _mm512_setzero_ps(), _CMP_GT_OQ), v);
}
// c != 0 ? a : b per lane.
[[gnu::always_inline]] inline V vselect_nonzero(V c, V a, V b) {
  return _mm512_mask_mov_ps(b, _mm512_cmp_ps_mask(c, _mm512_setzero_ps(), _CMP_NEQ_UQ), a);
}

#include "techniques/rt/atrous_simd.inl"

}  // namespace shadowlab::atrous_avx512
#endif
