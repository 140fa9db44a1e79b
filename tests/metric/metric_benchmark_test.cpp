// Timing of the whole metric at the paper's 1024×768, not a test: disabled by default. Run with
//   ./build-metric/tests/test_metric --gtest_also_run_disabled_tests
//       --gtest_filter='MetricBenchmark.*'   (one command line)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "core/parallel.h"
#include "core/timer.h"
#include "metric/box_blur.h"
#include "metric/contour.h"
#include "metric/coverage.h"
#include "metric/detail.h"
#include "metric/image_error.h"
#include "metric/roughness.h"
#include "metric/shadow_metric.h"
#include "metric/ssim.h"

namespace shadowlab {
namespace {

// Soft shadows of a few discs plus 1 % speckle (acne-like), 1024×768.
ImageF bench_mask(uint32_t seed, double shift) {
  ImageF m(1024, 768, 1);
  std::mt19937 rng(seed);
  for (int y = 0; y < 768; ++y)
    for (int x = 0; x < 1024; ++x) {
      double v = 1.0;
      for (int i = 0; i < 4; ++i) {
        const double cx = 200 + 200 * i + shift, cy = 300 + 80 * (i % 2), r = 60 + 20 * i;
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        v = std::min(v, std::clamp((d - r) / 8.0 + 0.5, 0.0, 1.0));
      }
      if (rng() % 100 == 0) v = 1.0 - v;
      m.at(x, y) = float(v);
    }
  return m;
}

TEST(MetricBenchmark, DISABLED_Full1024x768) {
  const ImageF ref = bench_mask(1, 0.0);
  const ImageF test = bench_mask(2, 3.0);
  ImageU32 texels(1024, 768, 1);
  for (int y = 0; y < 768; ++y)
    for (int x = 0; x < 1024; ++x) texels.at(x, y) = uint32_t((y / 2) * 512 + x / 2);
  const Timings t{12.0, 8.0};
  const int saved = thread_count();
  for (const int n : {1, 2}) {
    set_thread_count(n);
    compute_metric(test, ref, &texels, &t);  // warm-up
    std::vector<double> runs, reused;
    MetricScratch scratch;
    for (int i = 0; i < 21; ++i) {
      runs.push_back(median_ms(1, [&] { compute_metric(test, ref, &texels, &t); }));
      reused.push_back(median_ms(1, [&] { compute_metric(test, ref, &texels, &t, {}, &scratch); }));
    }
    std::sort(runs.begin(), runs.end());
    std::sort(reused.begin(), reused.end());
    // Stage breakdown (the calls compute_metric makes, here one after the other).
    const int k = blur_kernel_size(1024, 768);
    ImageD bt, br;
    const double blur = median_ms(9, [&] {
      bt = box_blur(test, k);
      br = box_blur(ref, k);
    });
    const double contours = median_ms(9, [&] { contour_scores(bt, br); });
    const double coverage = median_ms(9, [&] { dark_coverage(bt, br), lit_coverage(bt, br); });
    const double rough = median_ms(9, [&] { roberts_sums(test, ref, br); });
    const double detail = median_ms(9, [&] { detail_score(&texels); });
    const double structural = median_ms(9, [&] { ssim(test, ref); });
    const double error = median_ms(9, [&] { rmse(test, ref); });
    std::printf(
        "threads %d: compute_metric 1024x768 min %.2f ms, median %.2f ms; with a reused "
        "MetricScratch min %.2f ms, median %.2f ms (21 runs each)\n  stages one by one: blur "
        "%.2f, contours %.2f, coverage %.2f, roberts %.2f, detail %.2f, ssim %.2f, rmse %.2f\n",
        n, runs.front(), runs[runs.size() / 2], reused.front(), reused[reused.size() / 2], blur,
        contours, coverage, rough, detail, structural, error);
  }
  set_thread_count(saved);
}

}  // namespace
}  // namespace shadowlab
