#include "metric/visible_difference.h"

#include <algorithm>
#include <cmath>

#include "metric/box_blur.h"

namespace shadowlab {

VisibleDifference visible_difference(const ImageF& ref, const ImageF& test) {
  if (ref.channels != 1 || test.channels != 1 || ref.width != test.width ||
      ref.height != test.height)
    throw InputError("visible difference", "needs two 1-channel images of the same size");
  VisibleDifference out;
  const size_t n = ref.pixel_count();
  if (n == 0) return out;
  // Local variance of the reference from box means of v and v² (double; clamp tiny negatives).
  ImageF sq = ref;
  for (float& v : sq.data) v = v * v;
  const ImageD mean = box_blur(ref, kMaskingWindow);
  const ImageD mean_sq = box_blur(sq, kMaskingWindow);
  size_t plain = 0, masked = 0;
  for (size_t i = 0; i < n; ++i) {
    const double diff = std::fabs(double(test.data[i]) - double(ref.data[i]));
    if (!(diff > kVisibleThreshold)) continue;
    ++plain;
    const double var = std::max(0.0, mean_sq.data[i] - mean.data[i] * mean.data[i]);
    const double elevation = std::max(1.0, std::pow(std::sqrt(var) / kVisibleThreshold, kMaskingSlope));
    if (diff > kVisibleThreshold * elevation) ++masked;
  }
  out.plain = double(plain) / double(n);
  out.masked = double(masked) / double(n);
  return out;
}

}  // namespace shadowlab
