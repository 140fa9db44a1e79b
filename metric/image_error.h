#pragma once
// Plain per-pixel error of two masks: RMSE and PSNR (extra columns, docs/design.md §5.9).
#include "core/image.h"

namespace shadowlab {

// PSNR reported for identical images (and the cap for nearly identical ones), dB. A finite cap
// keeps tables, CSV and JSON free of inf; 100 dB means RMSE ≤ 1e-5 on data range 1.
constexpr double kPsnrCapDb = 100.0;

// √(mean over pixels of (a − b)²) of two 1-channel images of the same size; per-row sums in
// double, added in row order.
double rmse(const ImageF& a, const ImageF& b);

// PSNR for data range 1: min(kPsnrCapDb, −20·log10(rmse)); kPsnrCapDb when rmse is 0.
double psnr_from_rmse(double rmse);

}  // namespace shadowlab
