#include "metric/image_error.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"

namespace shadowlab {

double rmse(const ImageF& a, const ImageF& b) {
  if (a.width != b.width || a.height != b.height || a.channels != 1 || b.channels != 1 || a.empty())
    throw InputError("metric", "RMSE needs two non-empty 1-channel images of the same size");
  const size_t W = size_t(a.width);
  const size_t H = size_t(a.height);
  std::vector<double> row_sum(H, 0.0);
  parallel_for_chunks(H, 32, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y) {
      const float* pa = a.plane(0) + y * W;
      const float* pb = b.plane(0) + y * W;
      double s = 0.0;
      for (size_t x = 0; x < W; ++x) {
        const double d = double(pa[x]) - double(pb[x]);
        s += d * d;
      }
      row_sum[y] = s;
    }
  });
  double total = 0.0;
  for (const double s : row_sum) total += s;
  return std::sqrt(total / (double(W) * double(H)));
}

double psnr_from_rmse(double rmse) {
  SL_CHECK(rmse >= 0.0);
  if (rmse == 0.0) return kPsnrCapDb;
  return std::min(kPsnrCapDb, -20.0 * std::log10(rmse) + 0.0);  // + 0.0: no −0 at rmse = 1
}

}  // namespace shadowlab
