#pragma once
// Acne (noise in the lit region) and noise (in the dark region) via the Roberts cross
// (docs/design.md §5.5).
#include <cstddef>

#include "core/image.h"
#include "metric/box_blur.h"

namespace shadowlab {

// Roberts-cross magnitude of cell (x, y), x < W−1, y < H−1:
// g = √((m(x,y) − m(x+1,y+1))² + (m(x+1,y) − m(x,y+1))²).
double roberts_cross(const ImageF& mask, int x, int y);

// Sums of g² over the cells of one region, for the test and the reference mask.
struct RobertsRegion {
  size_t cells = 0;     // cells whose top-left pixel lies in the region
  double test_sum = 0;  // Σ g² of the test mask over those cells
  double ref_sum = 0;   // Σ g² of the reference mask over those cells
};
struct RobertsSums {
  RobertsRegion lit;   // cells with B_R > 0.9 at the top-left pixel (acne)
  RobertsRegion dark;  // cells with B_R < 0.1 at the top-left pixel (noise)
};

// One pass over all cells of the unblurred test and reference masks, the regions taken from the
// blurred reference. Rows are summed in row order, so the result is thread-count independent.
RobertsSums roberts_sums(const ImageF& test, const ImageF& ref, const ImageD& blurred_ref);

// clamp(min((1 − T_RMS)/(1 − R_RMS), 1), 0, 1); when 1 − R_RMS ≤ 0: 1 if T_RMS ≤ R_RMS, else 0.
double roughness_score(double test_rms, double ref_rms);

// The score of one region, T_RMS = √(test_sum/cells), R_RMS = √(ref_sum/cells); 1 when empty.
double roughness_score(const RobertsRegion& region);

// Acne score (lit region) and noise score (dark region) of unblurred masks.
double acne_score(const ImageF& test, const ImageF& ref, const ImageD& blurred_ref);
double noise_score(const ImageF& test, const ImageF& ref, const ImageD& blurred_ref);

}  // namespace shadowlab
