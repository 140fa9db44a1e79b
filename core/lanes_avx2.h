#pragma once
// The lanes of the AVX2 kernel files (*_avx2.cpp, compiled with -mavx2 -mfma; docs/simd.md): 8
// floats, and the operations a kernel body written once for AVX2 and AVX-512 (a .inl) uses.
// core/lanes_avx512.h defines the same names for 16 floats. Each is one instruction (two for
// vpositive), forced inline, so no lane function exists out of line to be shared with code of
// another instruction set.
#include <immintrin.h>

namespace shadowlab::lanes_avx2 {

using Vf = __m256;
constexpr int kLanes = 8;

[[gnu::always_inline]] inline Vf vzero() { return _mm256_setzero_ps(); }
[[gnu::always_inline]] inline Vf vset1(float v) { return _mm256_set1_ps(v); }
[[gnu::always_inline]] inline Vf vloadu(const float* p) { return _mm256_loadu_ps(p); }
// p aligned to the vector's size.
[[gnu::always_inline]] inline void vstore(float* p, Vf v) { _mm256_store_ps(p, v); }
[[gnu::always_inline]] inline void vstoreu(float* p, Vf v) { _mm256_storeu_ps(p, v); }
[[gnu::always_inline]] inline Vf vadd(Vf a, Vf b) { return _mm256_add_ps(a, b); }
[[gnu::always_inline]] inline Vf vsub(Vf a, Vf b) { return _mm256_sub_ps(a, b); }
[[gnu::always_inline]] inline Vf vmul(Vf a, Vf b) { return _mm256_mul_ps(a, b); }
// v where v > 0, else +0 (a NaN gives +0): v > 0 ? v : 0 per lane.
[[gnu::always_inline]] inline Vf vpositive(Vf v) {
  return _mm256_and_ps(v, _mm256_cmp_ps(v, _mm256_setzero_ps(), _CMP_GT_OQ));
}

}  // namespace shadowlab::lanes_avx2
