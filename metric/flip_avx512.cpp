// The AVX-512 table of metric/flip_kernels.h: power() in 8 lanes (exp_d8, log_d8), and the
// filter rows of flip_rows.inl vectorized for this set. Compiled with -mavx512f -mavx512vl
// -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstring>

#include "core/exp_log_avx512.h"

namespace shadowlab::flip_avx512 {

size_t power(const double* x, const double* p, double p0, size_t n, double* out) {
  size_t i = 0;
  const __m512d tiny = _mm512_set1_pd(0x1p-1000), zero = _mm512_setzero_pd(),
                one = _mm512_set1_pd(1.0);
  for (; i + 8 <= n; i += 8) {
    const __m512d v = _mm512_loadu_pd(x + i), e = p ? _mm512_loadu_pd(p + i) : _mm512_set1_pd(p0);
    const __m512d y = exp_log_avx512::exp_d8(
        _mm512_mul_pd(e, exp_log_avx512::log_d8(_mm512_maskz_max_pd(0xFF, v, tiny))));
    __m512d r = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(v, tiny, _CMP_LT_OQ), y, zero);
    r = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(e, zero, _CMP_EQ_OQ), r, one);
    _mm512_storeu_pd(out + i, r);
  }
  return i;
}

#include "metric/flip_rows.inl"

}  // namespace shadowlab::flip_avx512
#endif
