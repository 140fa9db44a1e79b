#include "metric/ssim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"

namespace shadowlab {
namespace {

constexpr int kRadius = kSsimWindow / 2;

std::array<double, kSsimWindow> gaussian_weights() {
  std::array<double, kSsimWindow> w{};
  double sum = 0.0;
  for (int i = 0; i < kSsimWindow; ++i) {
    const double d = double(i - kRadius);
    w[size_t(i)] = std::exp(-d * d / (2.0 * kSsimSigma * kSsimSigma));
    sum += w[size_t(i)];
  }
  for (double& v : w) v /= sum;
  return w;
}

// Window centres of one dimension: [begin, end).
struct Range {
  int begin, end;
};
Range centres(int size) {
  return size >= kSsimWindow ? Range{kRadius, size - kRadius} : Range{0, size};
}

}  // namespace

double ssim_from_moments(double mean_a, double mean_b, double var_a, double var_b, double cov_ab) {
  const double num = (2.0 * mean_a * mean_b + kSsimC1) * (2.0 * cov_ab + kSsimC2);
  const double den = (mean_a * mean_a + mean_b * mean_b + kSsimC1) * (var_a + var_b + kSsimC2);
  return num / den;
}

double ssim(const ImageF& a, const ImageF& b) {
  if (a.width != b.width || a.height != b.height || a.channels != 1 || b.channels != 1 || a.empty())
    throw InputError("metric", "SSIM needs two non-empty 1-channel images of the same size");
  const int w = a.width;
  const int h = a.height;
  const size_t W = size_t(w);
  const auto weight = gaussian_weights();
  const Range rx = centres(w);
  const Range ry = centres(h);
  const size_t out_w = size_t(rx.end - rx.begin);
  const size_t out_h = size_t(ry.end - ry.begin);
  // Padded row: column x of the image sits at index x + kRadius; the pads repeat the edges.
  const size_t P = W + 2 * kRadius;
  // The window is symmetric (weight[i] = weight[10 − i]), so taps i and 10 − i share one
  // multiplication: Σ = w5·v5 + Σ_{i<5} w_i·(v_i + v_{10−i}), summed in that order. Pixel loops
  // are innermost so they vectorize.
  const double w5 = weight[kRadius];

  std::vector<double> row_sum(out_h, 0.0);
  // weight and w5 are captured by value: as locals the compiler knows the stores below cannot
  // change them, which lets the pixel loops vectorize.
  parallel_for_chunks(out_h, 8, [&, weight, w5](size_t i0, size_t i1) {
    // Vertically filtered a, b, a², b², ab of one output row, padded horizontally.
    std::array<std::vector<double>, 5> v;
    for (auto& c : v) c.resize(P);
    std::vector<double> local(out_w);  // SSIM of each window of the row
    for (size_t i = i0; i < i1; ++i) {
      const int y = ry.begin + int(i);
      const float* ra[kSsimWindow];
      const float* rb[kSsimWindow];
      for (int j = 0; j < kSsimWindow; ++j) {
        const size_t sy = size_t(std::clamp(y - kRadius + j, 0, h - 1));
        ra[j] = a.plane(0) + sy * W;
        rb[j] = b.plane(0) + sy * W;
      }
      double* va = v[0].data() + kRadius;
      double* vb = v[1].data() + kRadius;
      double* vaa = v[2].data() + kRadius;
      double* vbb = v[3].data() + kRadius;
      double* vab = v[4].data() + kRadius;
      // Centre row and the outermost pair first, then the pairs 1, 9 … 4, 6.
      {
        const double w0 = weight[0];
        const float* a5 = ra[kRadius];
        const float* b5 = rb[kRadius];
        const float* a0 = ra[0];
        const float* a1 = ra[kSsimWindow - 1];
        const float* b0 = rb[0];
        const float* b1 = rb[kSsimWindow - 1];
        for (size_t x = 0; x < W; ++x) {
          const double p = a5[x], q = b5[x];
          const double p0 = a0[x], p1 = a1[x], q0 = b0[x], q1 = b1[x];
          va[x] = w5 * p + w0 * (p0 + p1);
          vb[x] = w5 * q + w0 * (q0 + q1);
          vaa[x] = w5 * (p * p) + w0 * (p0 * p0 + p1 * p1);
          vbb[x] = w5 * (q * q) + w0 * (q0 * q0 + q1 * q1);
          vab[x] = w5 * (p * q) + w0 * (p0 * q0 + p1 * q1);
        }
      }
      for (int j = 1; j < kRadius; ++j) {  // the row pair j, 10 − j
        const double wj = weight[size_t(j)];
        const float* a0 = ra[j];
        const float* a1 = ra[kSsimWindow - 1 - j];
        const float* b0 = rb[j];
        const float* b1 = rb[kSsimWindow - 1 - j];
        for (size_t x = 0; x < W; ++x) {
          const double p0 = a0[x], p1 = a1[x], q0 = b0[x], q1 = b1[x];
          va[x] += wj * (p0 + p1);
          vb[x] += wj * (q0 + q1);
          vaa[x] += wj * (p0 * p0 + p1 * p1);
          vbb[x] += wj * (q0 * q0 + q1 * q1);
          vab[x] += wj * (p0 * q0 + p1 * q1);
        }
      }
      for (auto& c : v) {
        std::fill(c.begin(), c.begin() + kRadius, c[kRadius]);
        std::fill(c.end() - kRadius, c.end(), c[kRadius + W - 1]);
      }
      // Horizontal filter at the window centres: centre x reads padded indices x … x + 10.
      const double* pa = v[0].data() + rx.begin;
      const double* pb = v[1].data() + rx.begin;
      const double* paa = v[2].data() + rx.begin;
      const double* pbb = v[3].data() + rx.begin;
      const double* pab = v[4].data() + rx.begin;
      for (size_t t = 0; t < out_w; ++t) {
        double ma = w5 * pa[t + kRadius], mb = w5 * pb[t + kRadius];
        double maa = w5 * paa[t + kRadius], mbb = w5 * pbb[t + kRadius];
        double mab = w5 * pab[t + kRadius];
#pragma GCC unroll 5
        for (int k = 0; k < kRadius; ++k) {
          const double wk = weight[size_t(k)];
          const size_t l = t + size_t(k), r = t + size_t(kSsimWindow - 1 - k);
          ma += wk * (pa[l] + pa[r]);
          mb += wk * (pb[l] + pb[r]);
          maa += wk * (paa[l] + paa[r]);
          mbb += wk * (pbb[l] + pbb[r]);
          mab += wk * (pab[l] + pab[r]);
        }
        local[t] = ssim_from_moments(ma, mb, maa - ma * ma, mbb - mb * mb, mab - ma * mb);
      }
      // Summed apart from the loop above so that loop has no serial dependency.
      double s = 0.0;
      for (size_t t = 0; t < out_w; ++t) s += local[t];
      row_sum[i] = s;
    }
  });
  double total = 0.0;
  for (const double s : row_sum) total += s;
  return total / (double(out_w) * double(out_h));
}

}  // namespace shadowlab
