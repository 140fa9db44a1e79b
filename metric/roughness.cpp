#include "metric/roughness.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "metric/coverage.h"

namespace shadowlab {

double roberts_cross(const ImageF& m, int x, int y) {
  SL_CHECK(x >= 0 && y >= 0 && x + 1 < m.width && y + 1 < m.height);
  const double a = double(m.at(x, y)) - double(m.at(x + 1, y + 1));
  const double b = double(m.at(x + 1, y)) - double(m.at(x, y + 1));
  return std::sqrt(a * a + b * b);
}

RobertsSums roberts_sums(const ImageF& test, const ImageF& ref, const ImageD& blurred_ref) {
  if (test.width != ref.width || test.height != ref.height || blurred_ref.width != ref.width ||
      blurred_ref.height != ref.height || test.channels != 1 || ref.channels != 1 ||
      blurred_ref.channels != 1)
    throw InputError("metric", "Roberts cross needs 1-channel images of the same size");
  RobertsSums total;
  if (ref.width < 2 || ref.height < 2) return total;  // no cells
  const size_t W = size_t(ref.width);
  const size_t cells_y = size_t(ref.height) - 1;
  std::vector<RobertsSums> rows(cells_y);
  parallel_for_chunks(cells_y, 16, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y) {
      const float* t0 = test.plane(0) + y * W;
      const float* t1 = t0 + W;
      const float* r0 = ref.plane(0) + y * W;
      const float* r1 = r0 + W;
      const double* b = blurred_ref.plane(0) + y * W;
      RobertsSums s;
      for (size_t x = 0; x + 1 < W; ++x) {
        const bool lit = is_lit(b[x]);
        const bool dark = is_dark(b[x]);
        if (!lit && !dark) continue;
        // g² directly: the RMS never needs g itself.
        const double ta = double(t0[x]) - double(t1[x + 1]);
        const double tb = double(t0[x + 1]) - double(t1[x]);
        const double ra = double(r0[x]) - double(r1[x + 1]);
        const double rb = double(r0[x + 1]) - double(r1[x]);
        RobertsRegion& region = lit ? s.lit : s.dark;
        ++region.cells;
        region.test_sum += ta * ta + tb * tb;
        region.ref_sum += ra * ra + rb * rb;
      }
      rows[y] = s;
    }
  });
  for (const RobertsSums& s : rows) {
    total.lit.cells += s.lit.cells;
    total.lit.test_sum += s.lit.test_sum;
    total.lit.ref_sum += s.lit.ref_sum;
    total.dark.cells += s.dark.cells;
    total.dark.test_sum += s.dark.test_sum;
    total.dark.ref_sum += s.dark.ref_sum;
  }
  return total;
}

double roughness_score(double test_rms, double ref_rms) {
  const double denom = 1.0 - ref_rms;
  if (denom <= 0.0) return test_rms <= ref_rms ? 1.0 : 0.0;
  return std::clamp(std::min((1.0 - test_rms) / denom, 1.0), 0.0, 1.0);
}

double roughness_score(const RobertsRegion& region) {
  if (region.cells == 0) return 1.0;
  const double n = double(region.cells);
  return roughness_score(std::sqrt(region.test_sum / n), std::sqrt(region.ref_sum / n));
}

double acne_score(const ImageF& test, const ImageF& ref, const ImageD& blurred_ref) {
  return roughness_score(roberts_sums(test, ref, blurred_ref).lit);
}

double noise_score(const ImageF& test, const ImageF& ref, const ImageD& blurred_ref) {
  return roughness_score(roberts_sums(test, ref, blurred_ref).dark);
}

}  // namespace shadowlab
