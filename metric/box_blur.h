#pragma once
// The metric's blur (docs/design.md §5.1): a k×k box mean with clamp-to-edge borders, accumulated in
// double and kept in double so the contour and coverage thresholds see no float rounding.
#include "core/image.h"

namespace shadowlab {

// Double-precision image (blurred masks, distance fields); same layout as Image<T>.
using ImageD = Image<double>;

// round-to-odd(x) = max(1, 2·⌊x/2⌋ + 1); x must be finite.
int round_to_odd(double x);

// Blur side k for a W×H mask: 11 at 1024×768, else round-to-odd(11·√(W·H)/√(1024·768)).
int blur_kernel_size(int width, int height);

// k×k box mean of a 1-channel image (k odd, ≥ 1), clamp-to-edge: out(x, y) is the mean of
// in(clamp(x + i), clamp(y + j)) for i, j in [−k/2, k/2]. Separable running sums in double
// (columns, then rows), one division by k² at the end, so a constant image blurs to itself
// exactly and a binary mask gives the correctly rounded n/k². The result does not depend on
// the thread count. Throws InputError for a multi-channel image or a bad k.
ImageD box_blur(const ImageF& image, int k);

// The same into `out` (reshaped to the image's size, its memory reused; every value written).
void box_blur(const ImageF& image, int k, ImageD& out);

}  // namespace shadowlab
