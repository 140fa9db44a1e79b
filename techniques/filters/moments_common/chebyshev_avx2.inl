// The AVX2 lane forms of techniques/filters/moments_common/chebyshev.h (4 doubles a vector), each performing the
// scalar function's operations in its order, so each lane gets its bits. Included inside the own
// namespace of a file compiled for AVX2 or AVX-512 (docs/simd.md), after <immintrin.h>.

// bilinear_weights for 4 lanes in double (fx, fy already widened from float).
[[gnu::always_inline]] inline void bilinear_weights4(__m256d fx, __m256d fy, __m256d w[4]) {
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d ox = _mm256_sub_pd(one, fx), oy = _mm256_sub_pd(one, fy);
  w[0] = _mm256_mul_pd(ox, oy);
  w[1] = _mm256_mul_pd(fx, oy);
  w[2] = _mm256_mul_pd(ox, fy);
  w[3] = _mm256_mul_pd(fx, fy);
}

// mixture_moments for 4 lanes in double: its operations in its order, so each lane gets its bits;
// in two halves (mean, then the variance about it) for callers that may skip the second.
[[gnu::always_inline]] inline __m256d mixture_mean4(const __m256d* w, const __m256d* A) {
  __m256d mean = _mm256_setzero_pd();
  for (int i = 0; i < 4; ++i) mean = _mm256_add_pd(mean, _mm256_mul_pd(w[i], A[i]));
  return mean;
}
[[gnu::always_inline]] inline __m256d mixture_variance4(const __m256d* w, const __m256d* A,
                                                        const __m256d* B, __m256d mean) {
  __m256d var = _mm256_setzero_pd();
  for (int i = 0; i < 4; ++i) {
    const __m256d dm = _mm256_sub_pd(A[i], mean);
    var = _mm256_add_pd(var, _mm256_mul_pd(w[i], _mm256_add_pd(B[i], _mm256_mul_pd(dm, dm))));
  }
  return var;
}
[[gnu::always_inline]] inline void mixture_moments4(const __m256d* w, const __m256d* A,
                                                    const __m256d* B, __m256d& mean,
                                                    __m256d& var) {
  mean = mixture_mean4(w, A);
  var = mixture_variance4(w, A, B, mean);
}

// chebyshev for 4 lanes in double, before its rounding to float: std::max(a, b) is
// a < b ? b : a and std::clamp likewise, as compare-and-blend, so each lane gets its bits.
[[gnu::always_inline]] inline __m256d chebyshev4(__m256d t, __m256d mean, __m256d var,
                                                 __m256d min_var, double bleed) {
  const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
  var = _mm256_blendv_pd(var, min_var, _mm256_cmp_pd(var, min_var, _CMP_LT_OQ));
  const __m256d diff = _mm256_sub_pd(t, mean);
  __m256d pmax = _mm256_div_pd(var, _mm256_add_pd(var, _mm256_mul_pd(diff, diff)));
  if (bleed > 0.0) {
    const __m256d b = _mm256_set1_pd(bleed);
    __m256d q = _mm256_div_pd(_mm256_sub_pd(pmax, b), _mm256_sub_pd(one, b));
    q = _mm256_blendv_pd(q, one, _mm256_cmp_pd(one, q, _CMP_LT_OQ));
    pmax = _mm256_blendv_pd(q, zero, _mm256_cmp_pd(q, zero, _CMP_LT_OQ));
  }
  return _mm256_blendv_pd(pmax, one, _mm256_cmp_pd(t, mean, _CMP_LE_OQ));
}
