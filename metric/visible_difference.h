#pragma once
// Shares of pixels where two shaded (grey, display-encoded) images visibly differ: the
// "visible difference" columns of the slide-projector LOD experiment (Dowling's claim is about
// what a viewer sees). Inputs are 1-channel images of display values in [0, 1] (sRGB-encoded
// luminance), the reference first.
//
// Two thresholds:
//   plain:  |test − ref| > t0 (t0 = 2/255: two 8-bit codes, about one just-noticeable step of
//           mid-grey on a display)
//   masked: |test − ref| > t0 · max(1, (σ_ref / t0)^0.7), σ_ref the reference's standard
//           deviation in a 7×7 box around the pixel: contrast masking as a threshold elevation
//           with Watson's (1993) slope 0.7, so the same error counts less on a busy pattern
//           (the masking the paper relies on) than on a smooth gradient.
// Both are blunt models — a share of pixels over a threshold, not a full visual difference
// predictor — and SSIM is reported beside them.
#include "core/image.h"

namespace shadowlab {

struct VisibleDifference {
  double plain = 0.0;   // share of pixels over the plain threshold, [0, 1]
  double masked = 0.0;  // share over the masked threshold, [0, 1] (<= plain)
};

constexpr double kVisibleThreshold = 2.0 / 255.0;
constexpr double kMaskingSlope = 0.7;
constexpr int kMaskingWindow = 7;

VisibleDifference visible_difference(const ImageF& reference, const ImageF& test);

}  // namespace shadowlab
