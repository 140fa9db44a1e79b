#pragma once
// Dark and lit area coverage (docs/design.md §5.4), and the region definitions the acne and noise
// scores reuse.
#include "metric/box_blur.h"

namespace shadowlab {

// A blurred value below kDarkLevel is dark, above kLitLevel is lit (strict inequalities).
constexpr double kDarkLevel = 0.1;
constexpr double kLitLevel = 0.9;

inline bool is_dark(double blurred) { return blurred < kDarkLevel; }
inline bool is_lit(double blurred) { return blurred > kLitLevel; }

// 1 − (pixels of the reference's dark region {B_R < 0.1} where B_T is not dark) / (pixels of
// that region); 1 when the region is empty. Blurred masks of the same size.
double dark_coverage(const ImageD& blurred_test, const ImageD& blurred_ref);

// The same for the lit region {B_R > 0.9} and B_T not lit.
double lit_coverage(const ImageD& blurred_test, const ImageD& blurred_ref);

}  // namespace shadowlab
