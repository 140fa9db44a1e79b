// The AVX2 table of metric/flip_kernels.h: power() in 4 lanes (exp_d4, log_d4), and the
// filter rows of flip_rows.inl vectorized for this set. Compiled with -mavx2 -mfma
// (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstring>

#include "core/exp_log_avx2.h"

namespace shadowlab::flip_avx2 {

size_t power(const double* x, const double* p, double p0, size_t n, double* out) {
  size_t i = 0;
  const __m256d tiny = _mm256_set1_pd(0x1p-1000), zero = _mm256_setzero_pd(),
                one = _mm256_set1_pd(1.0);
  for (; i + 4 <= n; i += 4) {
    const __m256d v = _mm256_loadu_pd(x + i), e = p ? _mm256_loadu_pd(p + i) : _mm256_set1_pd(p0);
    const __m256d y =
        exp_log_avx2::exp_d4(_mm256_mul_pd(e, exp_log_avx2::log_d4(_mm256_max_pd(v, tiny))));
    __m256d r = _mm256_blendv_pd(y, zero, _mm256_cmp_pd(v, tiny, _CMP_LT_OQ));
    r = _mm256_blendv_pd(r, one, _mm256_cmp_pd(e, zero, _CMP_EQ_OQ));
    _mm256_storeu_pd(out + i, r);
  }
  return i;
}

#include "metric/flip_rows.inl"

}  // namespace shadowlab::flip_avx2
#endif
