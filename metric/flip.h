#pragma once
// LDR-FLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and Fairchild, "FLIP: A
// Difference Evaluator for Alternating Images", HPG 2020): the perceptual error of a test image
// against a reference as a person sees them on a display, per pixel in [0, 1]; an extra column
// of the metric (docs/metric.md). Written from the paper's equations; the constants are the
// paper's as published with its reference implementation (NVlabs/flip, BSD-3).
//
// Colour pipeline: linear RGB → XYZ (D65) → YCxCz; each channel filtered by its spatial contrast
// sensitivity function (achromatic, red-green, blue-yellow: sums of Gaussians in visual degrees,
// normalized to sum 1, clamp-to-edge); back to linear RGB, clamped to [0, 1]; → CIELAB; Hunt
// adjustment (a, b scaled by L/100); HyAB distance |ΔL| + ‖(Δa, Δb)‖, raised to qc = 0.7 and
// mapped to [0, 1] piecewise linearly (pc = 0.4, pt = 0.95; cmax = the distance of green to
// blue). Feature pipeline: on the luminance Y of the unfiltered images, edge (first derivative
// of a Gaussian) and point (second derivative) detectors of standard deviation ½·0.082° in x
// and y, each kernel's positive weights normalized to sum 1 and its negative ones to −1; ΔEf =
// (max(|‖edge_R‖ − ‖edge_T‖|, |‖point_R‖ − ‖point_T‖|) / √2)^qf, qf = 0.5. FLIP = ΔEc^(1 − ΔEf).
//
// Every filter here is separable (a Gaussian, or a sum of two, times a polynomial in one
// coordinate), so it runs as a row pass and a column pass in double (tests/metric/flip_test.cpp
// checks it against the 2D sums straight from the equations).
#include <vector>

#include "core/image.h"

namespace shadowlab {

// Pixels per degree of visual angle of the default observer: a 0.7 m wide 3840-pixel display
// seen from 0.7 m, 3840 · π/180 (the paper's default, 67.02).
constexpr double kFlipPixelsPerDegree = 3840.0 * 3.14159265358979323846 / 180.0;

// Per-pixel LDR-FLIP of `test` against `ref`: images of 1 (grey: achromatic, Cx = Cz = 0) or 3
// channels, same size, holding LINEAR values (masks, shaded radiance); each value is clamped to [0,
// 1], which is what the sRGB PNG of the image shows (FLIP's first step, sRGB → linear, is then the
// identity). The result is 1 channel, same size. Throws InputError("flip", …) for empty or
// differently sized images, a channel count other than 1 or 3, a NaN, or pixels_per_degree
// outside [1, 1000]. Bit-identical for any thread count.
ImageF flip_error_map(const ImageF& test, const ImageF& ref,
                      double pixels_per_degree = kFlipPixelsPerDegree);

// One image's half of the work: its CSF-filtered, Hunt-adjusted CIELAB and the magnitudes of
// its edge and point features (w × h planes of doubles, row-major), so that a reference met by
// many tests (a sweep, a tune) is prepared once (MetricScratch keeps it).
struct FlipPrepared {
  int width = 0, height = 0;
  double pixels_per_degree = 0.0;
  std::vector<double> lab[3], edge, point;
};

// Throws as flip_error_map for a bad image or observer.
FlipPrepared flip_prepare(const ImageF& img, double pixels_per_degree = kFlipPixelsPerDegree);

// flip_error_map from two prepared images (same size and observer, else InputError).
ImageF flip_error_map(const FlipPrepared& test, const FlipPrepared& ref);

// Mean of an error map (per-row sums in double, added in row order).
double flip_mean(const ImageF& error_map);

// sRGB-encoded value in [0, 1] → linear (IEC 61966-2-1), for callers holding 8-bit-style images.
double srgb_to_linear(double v);

}  // namespace shadowlab
