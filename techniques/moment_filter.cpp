#include "techniques/moment_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"

namespace shadowlab {
namespace {

// Distance with "nothing seen" as the light's range.
inline float finite_dist(float d) { return d < 1.0f ? d : 1.0f; }

// Smaller-magnitude one-sided difference of a row/column sample (neighbours clamped).
inline double min_diff(double prev, double here, double next) {
  const double a = here - prev, b = next - here;
  return std::fabs(a) <= std::fabs(b) ? a : b;
}

// Separable box filter of N planes (T = double or float), clamp-to-edge, giving the mean over
// the k × k footprint: horizontal sums into tmp, then vertical sums into out. Every output is
// the same fixed-order sum of its window, whatever the chunking.
template <class T, int N>
void box_mean(const std::vector<T>* in, int w, int h, int k, std::vector<T>* tmp,
              std::vector<T>* out) {
  const int r = k / 2;
  const size_t n = size_t(w) * size_t(h);
  for (int c = 0; c < N; ++c) {
    tmp[c].resize(n);
    out[c].resize(n);
  }
  const T inv = T(1) / T(k * k);
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int c = 0; c < N; ++c) {
        const T* row = in[c].data() + y * size_t(w);
        T* dst = tmp[c].data() + y * size_t(w);
        // Borders clamp; the interior needs no index checks.
        auto clamped = [&](int x) {
          T s = 0;
          for (int i = -r; i <= r; ++i) s += row[std::clamp(x + i, 0, w - 1)];
          return s;
        };
        const int lo = std::min(r, w), hi = std::max(lo, w - r);
        for (int x = 0; x < lo; ++x) dst[x] = clamped(x);
        for (int x = lo; x < hi; ++x) {
          T s = 0;
          for (int i = -r; i <= r; ++i) s += row[x + i];
          dst[x] = s;
        }
        for (int x = hi; x < w; ++x) dst[x] = clamped(x);
      }
  });
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int c = 0; c < N; ++c) {
        T* dst = out[c].data() + y * size_t(w);
        const T* first = tmp[c].data() + size_t(std::clamp(int(y) - r, 0, h - 1)) * size_t(w);
        for (int x = 0; x < w; ++x) dst[x] = first[x];
        for (int j = -r + 1; j <= r; ++j) {
          const T* row = tmp[c].data() + size_t(std::clamp(int(y) + j, 0, h - 1)) * size_t(w);
          for (int x = 0; x < w; ++x) dst[x] += row[x];
        }
        for (int x = 0; x < w; ++x) dst[x] *= inv;
      }
  });
}

// Per-texel moments (d, d² [+ slope term]) in type T.
template <class T>
void raw_moments(const float* dist, int w, int h, bool slope_term, std::vector<T>& m1,
                 std::vector<T>& m2) {
  const size_t n = size_t(w) * size_t(h);
  m1.resize(n);
  m2.resize(n);
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = y * size_t(w) + size_t(x);
        const T d = T(finite_dist(dist[i]));
        m1[i] = d;
        m2[i] = d * d;
        if (slope_term) {
          auto at = [&](int xx, int yy) {
            return double(finite_dist(dist[size_t(std::clamp(yy, 0, h - 1)) * size_t(w) +
                                           size_t(std::clamp(xx, 0, w - 1))]));
          };
          const int yi = int(y);
          const double dx = min_diff(at(x - 1, yi), double(d), at(x + 1, yi));
          const double dy = min_diff(at(x, yi - 1), double(d), at(x, yi + 1));
          m2[i] += T(0.25 * (dx * dx + dy * dy));
        }
      }
  });
}

}  // namespace

void filter_moments_double(const float* dist, int w, int h, int k, bool slope_term,
                           std::vector<float>& mean, std::vector<float>& variance,
                           FilterScratch& scratch) {
  std::vector<double>* in = scratch.in;
  std::vector<double>* out = scratch.out;
  raw_moments<double>(dist, w, h, slope_term, in[0], in[1]);
  box_mean<double, 2>(in, w, h, k, scratch.tmp, out);
  const size_t n = size_t(w) * size_t(h);
  mean.resize(n);
  variance.resize(n);
  parallel_for_chunks(n, 1 << 14, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      mean[i] = float(out[0][i]);
      variance[i] = float(std::max(0.0, out[1][i] - out[0][i] * out[0][i]));
    }
  });
}

void filter_moments_fp32(const float* dist, int w, int h, int k, bool slope_term,
                         std::vector<float>& m1, std::vector<float>& m2) {
  std::vector<float> in[2], tmp[2], out[2];
  raw_moments<float>(dist, w, h, slope_term, in[0], in[1]);
  box_mean<float, 2>(in, w, h, k, tmp, out);
  m1.swap(out[0]);
  m2.swap(out[1]);
}

void filter_max(const float* dist, int w, int h, int k, std::vector<float>& out,
                FilterScratch& scratch) {
  const int r = k / 2;
  const size_t n = size_t(w) * size_t(h);
  std::vector<float>& tmp = scratch.tmp_f;
  tmp.resize(n);
  out.resize(n);
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int x = 0; x < w; ++x) {
        float m = 0.0f;
        for (int i = -r; i <= r; ++i)
          m = std::max(m, finite_dist(dist[y * size_t(w) + size_t(std::clamp(x + i, 0, w - 1))]));
        tmp[y * size_t(w) + size_t(x)] = m;
      }
  });
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y)
      for (int x = 0; x < w; ++x) {
        float m = 0.0f;
        for (int j = -r; j <= r; ++j)
          m = std::max(m, tmp[size_t(std::clamp(int(y) + j, 0, h - 1)) * size_t(w) + size_t(x)]);
        out[y * size_t(w) + size_t(x)] = m;
      }
  });
}

void filter_esm_log(const float* dist, int w, int h, int k, double c, std::vector<float>& out,
                    FilterScratch& scratch) {
  const size_t n = size_t(w) * size_t(h);
  // The image's smallest distance, a fixed-order reduction over per-row minima.
  std::vector<float> row_min(static_cast<size_t>(h));
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    for (size_t y = b; y < e; ++y) {
      float m = 1.0f;
      for (int x = 0; x < w; ++x) m = std::min(m, finite_dist(dist[y * size_t(w) + size_t(x)]));
      row_min[y] = m;
    }
  });
  double d_min = 1.0;
  for (float m : row_min) d_min = std::min(d_min, double(m));
  std::vector<double>* in = scratch.in;
  std::vector<double>* filtered = scratch.out;
  in[0].resize(n);
  parallel_for_chunks(n, 1 << 14, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) in[0][i] = std::exp(c * (double(finite_dist(dist[i])) - d_min));
  });
  box_mean<double, 1>(in, w, h, k, scratch.tmp, filtered);
  out.resize(n);
  parallel_for_chunks(n, 1 << 14, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) out[i] = float(c * d_min + std::log(filtered[0][i]));
  });
}

}  // namespace shadowlab
