// The AVX-512 row of techniques/nsm/nsm_conv.h: register tiles of NB blocks of 16 output
// channels × P pixels, each lane the oracle's chain of fused multiply-adds (bias, then ic, ky,
// kx ascending). Compiled with -mavx512f -mavx512vl -mavx512dq -mavx512bw -mfma (docs/simd.md);
// the explicit vfmadd is the family's documented exception to the no-FMA rule.
#if defined(__x86_64__)
#include <immintrin.h>

#include <cmath>
#include <cstddef>

#include "techniques/nsm/nsm_conv.h"

namespace shadowlab::nsm_conv_avx512 {

// w · x + acc with one rounding. SIMDe's portable fmadd (the emulated build) rounds the product
// and the sum apart, so there each lane calls std::fma, as the oracle does.
inline __m512 fmadd(__m512 w, __m512 x, __m512 acc) {
#if defined(SHADOWLAB_EMULATE_SIMD)
  alignas(64) float a[16], b[16], c[16];
  _mm512_store_ps(a, w);
  _mm512_store_ps(b, x);
  _mm512_store_ps(c, acc);
  for (int i = 0; i < 16; ++i) c[i] = std::fma(a[i], b[i], c[i]);
  return _mm512_load_ps(c);
#else
  return _mm512_fmadd_ps(w, x, acc);
#endif
}

template <int K, int NB, int P>
inline void tile(const NsmConvRowArgs& a, int x0, int b0) {
  constexpr int taps = K * K;
  const int cin = a.cin;
  const size_t bstride = size_t(cin) * taps * 16;
  const float* wb = a.weight + size_t(b0) * bstride;
  __m512 acc[NB][P];
  for (int b = 0; b < NB; ++b) {
    const __m512 bias = _mm512_loadu_ps(a.bias + size_t(b0 + b) * 16);
    for (int p = 0; p < P; ++p) acc[b][p] = bias;
  }
  // One (ic, ky, kx) step at a time: unrolled, the weights of three steps would join the
  // accumulators in registers and spill them.
  for (int ic = 0; ic < cin; ++ic)
#pragma GCC unroll 1
    for (int ky = 0; ky < K; ++ky) {
      const float* r = a.rows[ky] + size_t(x0) * cin + ic;
      const float* w = wb + (size_t(ic) * taps + ky * K) * 16;
#pragma GCC unroll 1
      for (int kx = 0; kx < K; ++kx) {
        __m512 wv[NB];
        for (int b = 0; b < NB; ++b) wv[b] = _mm512_loadu_ps(w + b * bstride + kx * 16);
        for (int p = 0; p < P; ++p) {
          const __m512 xv = _mm512_set1_ps(r[size_t(p + kx) * cin]);
          for (int b = 0; b < NB; ++b) acc[b][p] = fmadd(wv[b], xv, acc[b][p]);
        }
      }
    }
  const __m512 zero = _mm512_setzero_ps();
  for (int b = 0; b < NB; ++b) {
    const int oc0 = (b0 + b) * 16;
    const int n = a.cout - oc0 < 16 ? a.cout - oc0 : 16;
    const __mmask16 m = __mmask16((1u << n) - 1u);
    for (int p = 0; p < P; ++p) {
      // max(acc, 0) returns the second operand for NaN and for −0: the oracle's acc > 0 ? acc : +0
      // (the zero-masked form with every lane on: GCC 12's unmasked one trips
      // -Wmaybe-uninitialized, as in core/exp_log.h).
      const __m512 v = a.relu ? _mm512_maskz_max_ps(0xFFFF, acc[b][p], zero) : acc[b][p];
      float* o = a.out + size_t(x0 + p) * a.cout + oc0;
      if (n == 16) _mm512_storeu_ps(o, v);
      else _mm512_mask_storeu_ps(o, m, v);
    }
  }
}

template <int K, int NB, int P>
inline void blocks_span(const NsmConvRowArgs& a, int b0) {
  int x = 0;
  for (; x + P <= a.width; x += P) tile<K, NB, P>(a, x, b0);
  for (; x < a.width; ++x) tile<K, NB, 1>(a, x, b0);
}

template <int K>
inline void row_k(const NsmConvRowArgs& a) {
  const int blocks = (a.cout + 15) / 16;
  int b0 = 0;
  for (; b0 + 4 <= blocks; b0 += 4) blocks_span<K, 4, 6>(a, b0);
  switch (blocks - b0) {
    case 3: blocks_span<K, 3, 8>(a, b0); break;
    case 2: blocks_span<K, 2, 12>(a, b0); break;
    case 1: blocks_span<K, 1, 14>(a, b0); break;
    default: break;
  }
}

void row(const NsmConvRowArgs& a) {
  if (a.k == 3) row_k<3>(a);
  else row_k<1>(a);
}

}  // namespace shadowlab::nsm_conv_avx512
#endif
