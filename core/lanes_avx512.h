#pragma once
// The lanes of the AVX-512 kernel files (*_avx512.cpp, compiled with -mavx512f -mavx512vl
// -mavx512dq -mavx512bw; docs/simd.md): 16 floats, under the names core/lanes_avx2.h gives its 8,
// so that one kernel body (a .inl) serves both.
#include <immintrin.h>

namespace shadowlab::lanes_avx512 {

using Vf = __m512;
constexpr int kLanes = 16;

[[gnu::always_inline]] inline Vf vzero() { return _mm512_setzero_ps(); }
[[gnu::always_inline]] inline Vf vset1(float v) { return _mm512_set1_ps(v); }
[[gnu::always_inline]] inline Vf vloadu(const float* p) { return _mm512_loadu_ps(p); }
// p aligned to the vector's size.
[[gnu::always_inline]] inline void vstore(float* p, Vf v) { _mm512_store_ps(p, v); }
[[gnu::always_inline]] inline void vstoreu(float* p, Vf v) { _mm512_storeu_ps(p, v); }
[[gnu::always_inline]] inline Vf vadd(Vf a, Vf b) { return _mm512_add_ps(a, b); }
[[gnu::always_inline]] inline Vf vsub(Vf a, Vf b) { return _mm512_sub_ps(a, b); }
[[gnu::always_inline]] inline Vf vmul(Vf a, Vf b) { return _mm512_mul_ps(a, b); }
// v where v > 0, else +0 (a NaN gives +0): v > 0 ? v : 0 per lane.
[[gnu::always_inline]] inline Vf vpositive(Vf v) {
  return _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(v, _mm512_setzero_ps(), _CMP_GT_OQ), v);
}

}  // namespace shadowlab::lanes_avx512
