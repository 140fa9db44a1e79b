#pragma once
// Chebyshev's one-sided bound and the bilinear mixture of centred moments, shared by the
// moment filters that store (mean, variance) per texel: vsm (variance_map.cpp) and evsm
// (exponential_variance_map.cpp). docs/design.md §6 (VSM, EVSM) gives the model. The lane
// forms for the lookups' vector batches: techniques/chebyshev_avx2.inl.
#include <algorithm>

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


}  // namespace shadowlab
