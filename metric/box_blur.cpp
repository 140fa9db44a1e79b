#include "metric/box_blur.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metric/image_reuse.h"

namespace shadowlab {

int round_to_odd(double x) {
  SL_CHECK(std::isfinite(x));
  const double odd = 2.0 * std::floor(x / 2.0) + 1.0;
  return odd < 1.0 ? 1 : int(odd);
}

int blur_kernel_size(int width, int height) {
  if (width <= 0 || height <= 0)
    throw InputError("metric", "blur size needs a non-empty image, got " + std::to_string(width) +
                                   "x" + std::to_string(height));
  // The paper's calibration point; spelled out so it never depends on sqrt rounding.
  if (width == 1024 && height == 768) return 11;
  const double scale = std::sqrt(double(width) * double(height)) / std::sqrt(1024.0 * 768.0);
  return round_to_odd(11.0 * scale);
}

ImageD box_blur(const ImageF& image, int k) {
  ImageD out;
  box_blur(image, k, out);
  return out;
}

void box_blur(const ImageF& image, int k, ImageD& out) {
  if (image.channels != 1)
    throw InputError("metric", "box blur expects a 1-channel image, got " +
                                   std::to_string(image.channels) + " channels");
  if (k < 1 || k % 2 == 0)
    throw InputError("metric", "box blur size must be odd and >= 1, got " + std::to_string(k));
  const int w = image.width;
  const int h = image.height;
  reshape_image(out, w, h);
  if (image.empty()) return;
  const int r = k / 2;
  const size_t W = size_t(w);
  const float* src = image.plane(0);
  double* dst = out.plane(0);

  // Vertical pass straight into `out`: un-normalized running column sums over chunks of
  // columns (cache friendly; every column is computed the same way whatever the chunking).
  parallel_for_chunks(W, 256, [&, r](size_t x0, size_t x1) {
    const size_t n = x1 - x0;
    std::vector<double> acc(n, 0.0);
    auto row = [&](long y) { return src + size_t(std::clamp(y, 0L, long(h) - 1)) * W + x0; };
    for (long j = -r; j <= r; ++j) {
      const float* in = row(j);
      for (size_t i = 0; i < n; ++i) acc[i] += in[i];
    }
    for (long y = 0; y < h; ++y) {
      double* o = dst + size_t(y) * W + x0;
      for (size_t i = 0; i < n; ++i) o[i] = acc[i];
      const float* add = row(y + r + 1);
      const float* sub = row(y - r);
      for (size_t i = 0; i < n; ++i) {
        acc[i] += add[i];
        acc[i] -= sub[i];
      }
    }
  });

  // Horizontal pass in place, row by row, then the single division by k². Each row is copied
  // with its clamped edge values as padding, so the running sum needs no index clamping:
  // sum(x) = pad[x] + … + pad[x + k − 1].
  const double kk = double(k) * double(k);
  parallel_for_chunks(size_t(h), 16, [&, r, k, kk](size_t y0, size_t y1) {
    std::vector<double> pad(W + size_t(2 * r) + 1);
    for (size_t y = y0; y < y1; ++y) {
      double* row = dst + y * W;
      for (size_t i = 0; i < pad.size(); ++i)
        pad[i] = row[size_t(std::clamp(long(i) - r, 0L, long(w) - 1))];
      double s = 0.0;
      for (int i = 0; i < k; ++i) s += pad[size_t(i)];
      for (size_t x = 0; x < W; ++x) {
        row[x] = s / kk;
        s += pad[x + size_t(k)];
        s -= pad[x];
      }
    }
  });
}

}  // namespace shadowlab
