#include "metric/coverage.h"

#include <vector>

#include "core/error.h"
#include "core/parallel.h"

namespace shadowlab {
namespace {

// 1 − misses/region for the region picked by `in_class` (applied to both images).
template <class InClass>
double coverage(const ImageD& bt, const ImageD& br, InClass in_class) {
  if (bt.width != br.width || bt.height != br.height || bt.channels != 1 || br.channels != 1)
    throw InputError("metric", "coverage needs two 1-channel images of the same size");
  const size_t n = br.pixel_count();
  constexpr size_t kGrain = 1 << 14;
  const size_t chunks = (n + kGrain - 1) / kGrain;
  std::vector<size_t> region(chunks, 0), misses(chunks, 0);
  const double* t = bt.plane(0);
  const double* r = br.plane(0);
  parallel_for_chunks(n, kGrain, [&](size_t b, size_t e) {
    size_t in = 0, miss = 0;
    for (size_t i = b; i < e; ++i) {
      const bool ref_in = in_class(r[i]);
      in += ref_in;
      miss += ref_in && !in_class(t[i]);
    }
    region[b / kGrain] = in;
    misses[b / kGrain] = miss;
  });
  size_t total = 0, missed = 0;
  for (size_t c = 0; c < chunks; ++c) {
    total += region[c];
    missed += misses[c];
  }
  if (total == 0) return 1.0;
  return 1.0 - double(missed) / double(total);
}

}  // namespace

double dark_coverage(const ImageD& blurred_test, const ImageD& blurred_ref) {
  return coverage(blurred_test, blurred_ref, [](double v) { return is_dark(v); });
}

double lit_coverage(const ImageD& blurred_test, const ImageD& blurred_ref) {
  return coverage(blurred_test, blurred_ref, [](double v) { return is_lit(v); });
}

}  // namespace shadowlab
