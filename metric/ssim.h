#pragma once
// Structural similarity (Wang, Bovik, Sheikh & Simoncelli 2004) of two masks, an extra column
// of the metric (docs/design.md §5.9).
#include "core/image.h"

namespace shadowlab {

// Window and constants: 11×11 Gaussian, σ = 1.5 (weights normalized to sum 1), data range 1,
// C1 = (0.01)², C2 = (0.03)².
constexpr int kSsimWindow = 11;
constexpr double kSsimSigma = 1.5;
constexpr double kSsimC1 = 0.01 * 0.01;
constexpr double kSsimC2 = 0.03 * 0.03;

// Mean SSIM of two 1-channel images of the same size (unblurred masks, values in [0, 1]).
// Border convention: in each dimension of at least 11 pixels the mean runs over the window
// positions that lie wholly inside the image ("valid" positions, as in Wang et al.'s reference
// code): centres 5 … size−6. A dimension shorter than 11 pixels has no valid position; there
// every pixel is a centre and the window reads clamp-to-edge. Local statistics in double; the
// mean is summed row by row in row order (thread-count independent).
double ssim(const ImageF& a, const ImageF& b);

// SSIM of one window from its Gaussian-weighted statistics (means, variances, covariance).
double ssim_from_moments(double mean_a, double mean_b, double var_a, double var_b, double cov_ab);

}  // namespace shadowlab
