#pragma once
// Contour lines of a blurred mask and the contour-match score (docs/design.md §5.2–5.3).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "metric/box_blur.h"
#include "metric/distance_transform.h"

namespace shadowlab {

// The three contour levels of the metric.
constexpr std::array<double, 3> kContourLevels = {0.1, 0.5, 0.9};

// Contour pixels at several levels at once (at most 8): bit l of pixel (x, y) is set when,
// over the values of the 2×2 block {(x,y), (x+1,y), (x,y+1), (x+1,y+1)} that lie inside the
// image, min ≤ levels[l] ≤ max (so a block whose values all equal the level counts).
ImageU8 contour_bits(const ImageD& blurred, std::span<const double> levels);

// The same into `out` (reshaped, memory reused, every value written).
void contour_bits(const ImageD& blurred, std::span<const double> levels, ImageU8& out);

// The same for one level: 1 on contour pixels, 0 elsewhere.
ImageU8 contour_mask(const ImageD& blurred, double level);

// Root-mean-square, over the pixels of ref_contour with (value & bits) != 0, of the Euclidean
// distance (pixels) to the nearest such pixel of test_contour, via the exact distance
// transform (evaluated only on rows that hold reference contour pixels). Same sizes;
// ref_contour must have a set pixel; +infinity when test_contour has none. Squared distances
// are summed as integers, so the result is exact up to the final division and square root.
double contour_distance_rms(const ImageU8& test_contour, const ImageU8& ref_contour,
                            uint8_t bits = 0xFF);

// Worst-case contour distance D_MAX = 0.2·√(W·H), pixels.
double contour_max_distance(int width, int height);

// CM = clamp(1 − D_RMS/D_MAX, 0, 1) at `level` for two blurred masks of the same size;
// 1 when neither has a contour, 0 when only one of them has.
double contour_score(const ImageD& blurred_test, const ImageD& blurred_ref, double level);

// Buffers of contour_scores, reusable across calls.
struct ContourScratch {
  ImageU8 test, ref;            // contour bits of the two images
  std::vector<int32_t> column;  // column phase of the distance transform
};

// The scores at the three kContourLevels (c10, c50, c90), sharing one contour pass per image.
std::array<double, 3> contour_scores(const ImageD& blurred_test, const ImageD& blurred_ref);
std::array<double, 3> contour_scores(const ImageD& blurred_test, const ImageD& blurred_ref,
                                     ContourScratch& scratch);

}  // namespace shadowlab
