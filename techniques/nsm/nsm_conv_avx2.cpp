// The AVX2 row of techniques/nsm/nsm_conv.h: register tiles of one block of 16 output channels
// (two 8-lane vectors) × 6 pixels, each lane the oracle's chain of fused multiply-adds (bias,
// then ic, ky, kx ascending). Compiled with -mavx2 -mfma (docs/simd.md); the explicit vfmadd is
// the family's documented exception to the no-FMA rule.
#if defined(__x86_64__)
#include <immintrin.h>

#include <cmath>
#include <cstddef>

#include "techniques/nsm/nsm_conv.h"

namespace shadowlab::nsm_conv_avx2 {

// w · x + acc with one rounding. SIMDe's portable fmadd (the emulated build) rounds the product
// and the sum apart, so there each lane calls std::fma, as the oracle does.
inline __m256 fmadd(__m256 w, __m256 x, __m256 acc) {
#if defined(SHADOWLAB_EMULATE_SIMD)
  alignas(32) float a[8], b[8], c[8];
  _mm256_store_ps(a, w);
  _mm256_store_ps(b, x);
  _mm256_store_ps(c, acc);
  for (int i = 0; i < 8; ++i) c[i] = std::fma(a[i], b[i], c[i]);
  return _mm256_load_ps(c);
#else
  return _mm256_fmadd_ps(w, x, acc);
#endif
}

// Lanes [0, n) of v stored to o (n in 1..8).
inline void store_first(float* o, __m256 v, int n) {
  if (n >= 8) {
    _mm256_storeu_ps(o, v);
    return;
  }
  const __m256i m = _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  _mm256_maskstore_ps(o, m, v);
}

template <int K, int P>
inline void tile(const NsmConvRowArgs& a, int x0, int b0) {
  constexpr int taps = K * K;
  const int cin = a.cin;
  const float* wb = a.weight + size_t(b0) * cin * taps * 16;
  __m256 lo[P], hi[P];
  const __m256 blo = _mm256_loadu_ps(a.bias + size_t(b0) * 16);
  const __m256 bhi = _mm256_loadu_ps(a.bias + size_t(b0) * 16 + 8);
  for (int p = 0; p < P; ++p) {
    lo[p] = blo;
    hi[p] = bhi;
  }
  for (int ic = 0; ic < cin; ++ic)
    for (int ky = 0; ky < K; ++ky) {
      const float* r = a.rows[ky] + size_t(x0) * cin + ic;
      const float* w = wb + (size_t(ic) * taps + ky * K) * 16;
      for (int kx = 0; kx < K; ++kx) {
        const __m256 w0 = _mm256_loadu_ps(w + kx * 16);
        const __m256 w1 = _mm256_loadu_ps(w + kx * 16 + 8);
        for (int p = 0; p < P; ++p) {
          const __m256 xv = _mm256_broadcast_ss(r + size_t(p + kx) * cin);
          lo[p] = fmadd(w0, xv, lo[p]);
          hi[p] = fmadd(w1, xv, hi[p]);
        }
      }
    }
  const __m256 zero = _mm256_setzero_ps();
  const int oc0 = b0 * 16;
  const int n = a.cout - oc0 < 16 ? a.cout - oc0 : 16;
  for (int p = 0; p < P; ++p) {
    // max(acc, 0) returns the second operand for NaN and for −0: the oracle's acc > 0 ? acc : +0.
    const __m256 v0 = a.relu ? _mm256_max_ps(lo[p], zero) : lo[p];
    const __m256 v1 = a.relu ? _mm256_max_ps(hi[p], zero) : hi[p];
    float* o = a.out + size_t(x0 + p) * a.cout + oc0;
    store_first(o, v0, n);
    if (n > 8) store_first(o + 8, v1, n - 8);
  }
}

template <int K>
inline void row_k(const NsmConvRowArgs& a) {
  const int blocks = (a.cout + 15) / 16;
  for (int b0 = 0; b0 < blocks; ++b0) {
    int x = 0;
    for (; x + 6 <= a.width; x += 6) tile<K, 6>(a, x, b0);
    for (; x < a.width; ++x) tile<K, 1>(a, x, b0);
  }
}

void row(const NsmConvRowArgs& a) {
  if (a.k == 3) row_k<3>(a);
  else row_k<1>(a);
}

}  // namespace shadowlab::nsm_conv_avx2
#endif
