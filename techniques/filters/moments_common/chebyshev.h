#pragma once
// Chebyshev's one-sided bound and the bilinear mixture of centred moments, shared by the
// moment filters that store (mean, variance) per texel: vsm (variance_map.cpp) and evsm
// (exponential_variance_map.cpp). docs/design.md §6 (VSM, EVSM) gives the model.
#include <algorithm>

#include "core/simd_target.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace shadowlab {

// P(x >= t) <= σ² / (σ² + (t − μ)²) for t > μ (1 otherwise), with the variance floor
// σ² >= min_var and the light-bleeding remap p -> linstep(bleed, 1, p).
inline float chebyshev(double t, double mean, double var, double min_var, double bleed) {
  if (t <= mean) return 1.0f;
  var = std::max(var, min_var);
  const double diff = t - mean;
  double pmax = var / (var + diff * diff);
  if (bleed > 0.0) pmax = std::clamp((pmax - bleed) / (1.0 - bleed), 0.0, 1.0);
  return float(pmax);
}

// The bilinear weights of taps (x0,y0), (x1,y0), (x0,y1), (x1,y1) for fractions fx, fy.
inline void bilinear_weights(float fx, float fy, double w[4]) {
  w[0] = (1.0 - fx) * (1.0 - fy);
  w[1] = double(fx) * (1.0 - fy);
  w[2] = (1.0 - fx) * double(fy);
  w[3] = double(fx) * double(fy);
}

// Mean and variance of the mixture of four texels' distributions (mean A[i], variance B[i])
// with weights w: μ = Σ w·A, σ² = Σ w·(B + (A − μ)²), with no cancellation.
inline void mixture_moments(const double w[4], const float* A, const float* B, double& mean,
                            double& var) {
  mean = 0.0;
  for (int i = 0; i < 4; ++i) mean += w[i] * A[i];
  var = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double dm = A[i] - mean;
    var += w[i] * (double(B[i]) + dm * dm);
  }
}

#if defined(__x86_64__)
// bilinear_weights for 4 lanes in double (fx, fy already widened from float).
SL_TARGET("avx2") inline void bilinear_weights4(__m256d fx, __m256d fy,
                                                __m256d w[4]) {
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d ox = _mm256_sub_pd(one, fx), oy = _mm256_sub_pd(one, fy);
  w[0] = _mm256_mul_pd(ox, oy);
  w[1] = _mm256_mul_pd(fx, oy);
  w[2] = _mm256_mul_pd(ox, fy);
  w[3] = _mm256_mul_pd(fx, fy);
}

// bilinear_weights for 8 lanes in double (AVX-512).
SL_TARGET("avx512f") inline void bilinear_weights8(__m512d fx, __m512d fy,
                                                   __m512d w[4]) {
  const __m512d one = _mm512_set1_pd(1.0);
  const __m512d ox = _mm512_sub_pd(one, fx), oy = _mm512_sub_pd(one, fy);
  w[0] = _mm512_mul_pd(ox, oy);
  w[1] = _mm512_mul_pd(fx, oy);
  w[2] = _mm512_mul_pd(ox, fy);
  w[3] = _mm512_mul_pd(fx, fy);
}

// mixture_moments for 4 lanes in double: its operations in its order, so each lane gets its bits;
// in two halves (mean, then the variance about it) for callers that may skip the second.
SL_TARGET("avx2") inline __m256d mixture_mean4(const __m256d* w, const __m256d* A) {
  __m256d mean = _mm256_setzero_pd();
  for (int i = 0; i < 4; ++i) mean = _mm256_add_pd(mean, _mm256_mul_pd(w[i], A[i]));
  return mean;
}
SL_TARGET("avx2") inline __m256d mixture_variance4(const __m256d* w,
                                                                const __m256d* A,
                                                                const __m256d* B, __m256d mean) {
  __m256d var = _mm256_setzero_pd();
  for (int i = 0; i < 4; ++i) {
    const __m256d dm = _mm256_sub_pd(A[i], mean);
    var = _mm256_add_pd(var, _mm256_mul_pd(w[i], _mm256_add_pd(B[i], _mm256_mul_pd(dm, dm))));
  }
  return var;
}
SL_TARGET("avx2") inline void mixture_moments4(const __m256d* w, const __m256d* A,
                                               const __m256d* B, __m256d& mean,
                                               __m256d& var) {
  mean = mixture_mean4(w, A);
  var = mixture_variance4(w, A, B, mean);
}

// chebyshev for 4 lanes in double, before its rounding to float: std::max(a, b) is
// a < b ? b : a and std::clamp likewise, as compare-and-blend, so each lane gets its bits.
SL_TARGET("avx2") inline __m256d chebyshev4(__m256d t, __m256d mean, __m256d var,
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
#endif

}  // namespace shadowlab
