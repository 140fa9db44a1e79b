#include "techniques/moment_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/exp_log.h"
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

// The fused separable box (the fast path of filter_moments_double and filter_esm_log): per
// chunk of output rows, each input row's k-wide horizontal sums are computed once into a small
// chunk buffer, then each output row sums its k rows of that buffer. Every output is the same
// sequence of double additions as box_mean's two passes (left to right, then top to bottom, then
// × 1/k²), so the results are bit-identical to it; the loops run over x, which the compiler
// vectorizes without reordering any one texel's additions.

// out[x] = Σ_{i=0}^{k-1} ext[x + i], added in i order (ext: the row extended by k/2 clamped
// texels on each side).
__attribute__((target_clones("avx2", "default"))) void hsum_row(const double* ext, int w, int k,
                                                               double* out) {
  for (int x = 0; x < w; ++x) out[x] = 0.0;
  for (int i = 0; i < k; ++i)
    for (int x = 0; x < w; ++x) out[x] += ext[x + i];
}

// dst[x] = (rows[0][x] + rows[1][x] + … + rows[k-1][x]) × inv, added in row order.
__attribute__((target_clones("avx2", "default"))) void vsum_rows(const double* const* rows, int w,
                                                                int k, double inv, double* dst) {
  for (int x = 0; x < w; ++x) dst[x] = rows[0][x];
  for (int j = 1; j < k; ++j)
    for (int x = 0; x < w; ++x) dst[x] += rows[j][x];
  for (int x = 0; x < w; ++x) dst[x] *= inv;
}

// Row r of raw_moments without the slope term: m1 = d, m2 = d² (d = finite_dist).
__attribute__((target_clones("avx2", "default"))) void moment_row(const float* row, int w,
                                                                 double* m1, double* m2) {
  for (int x = 0; x < w; ++x) {
    const double d = double(row[x] < 1.0f ? row[x] : 1.0f);
    m1[x] = d;
    m2[x] = d * d;
  }
}

// Mean and variance floats of filtered moment rows (filter_moments_double's storage).
__attribute__((target_clones("avx2", "default"))) void mean_variance_row(const double* m1,
                                                                        const double* m2, int w,
                                                                        float* mean, float* var) {
  for (int x = 0; x < w; ++x) {
    mean[x] = float(m1[x]);
    const double v = m2[x] - m1[x] * m1[x];
    var[x] = float(v > 0.0 ? v : 0.0);
  }
}

// ESM's exponential of one row: out[x] = e^(c·(d − d_min)), d = finite_dist (core/exp_log.h:
// the vectorized loop gives the scalar bits). Two loops: with the float → double conversion in
// the same loop the compiler kept it scalar.
__attribute__((target_clones("avx2", "default"))) void esm_exp_row(const float* row, int w,
                                                                  double c, double d_min,
                                                                  double* out) {
  for (int x = 0; x < w; ++x) out[x] = double(row[x] < 1.0f ? row[x] : 1.0f);
  for (int x = 0; x < w; ++x) out[x] = exp_d(c * (out[x] - d_min));
}

// ESM's occluder term of one filtered row: c·d_min + ln(filtered).
__attribute__((target_clones("avx2", "default"))) void esm_log_row(const double* filtered, int w,
                                                                  double c, double d_min,
                                                                  float* out) {
  for (int x = 0; x < w; ++x) out[x] = float(c * d_min + log_d(filtered[x]));
}

// Fills the r texels on each side of an extended row with its edge values (clamp to edge).
inline void extend_row(double* ext, int w, int r) {
  for (int i = 0; i < r; ++i) {
    ext[i] = ext[r];
    ext[size_t(w + r + i)] = ext[size_t(w + r - 1)];
  }
}

// Runs the fused box over `planes` planes. make_row(y, ext) fills the extended input rows of
// input row y (planes × (w + k − 1) doubles, plane after plane); finish_row(y, out) receives
// the filtered rows (planes × w doubles).
template <class MakeRow, class FinishRow>
void fused_box(int w, int h, int k, int planes, const MakeRow& make_row,
               const FinishRow& finish_row) {
  const int r = k / 2;
  const size_t ew = size_t(w) + size_t(k) - 1;
  const double inv = 1.0 / double(k * k);
  parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
    const int lo = std::max(0, int(b) - r), hi = std::min(h - 1, int(e) - 1 + r);
    const size_t rows = size_t(hi - lo + 1);
    // One uninitialized block (every value is written before it is read): a zero-filled
    // std::vector here was a sixth of the filter's time.
    const size_t n_ext = size_t(planes) * ew, n_hsum = rows * size_t(planes) * size_t(w);
    const std::unique_ptr<double[]> buf(new double[n_ext + n_hsum + size_t(planes) * size_t(w)]);
    double* const ext = buf.get();
    double* const hsum = ext + n_ext;
    double* const out = hsum + n_hsum;
    for (int y = lo; y <= hi; ++y) {
      make_row(y, ext);
      for (int c = 0; c < planes; ++c)
        hsum_row(ext + size_t(c) * ew, w, k,
                 hsum + (size_t(y - lo) * size_t(planes) + size_t(c)) * size_t(w));
    }
    std::vector<const double*> window(static_cast<size_t>(k));
    for (size_t y = b; y < e; ++y) {
      for (int c = 0; c < planes; ++c) {
        for (int j = -r; j <= r; ++j) {
          const int yy = std::clamp(int(y) + j, 0, h - 1);
          window[size_t(j + r)] = hsum + (size_t(yy - lo) * size_t(planes) + size_t(c)) * size_t(w);
        }
        vsum_rows(window.data(), w, k, inv, out + size_t(c) * size_t(w));
      }
      finish_row(y, out);
    }
  });
}

}  // namespace

void filter_moments_double(const float* dist, int w, int h, int k, bool slope_term,
                           std::vector<float>& mean, std::vector<float>& variance) {
  const size_t n = size_t(w) * size_t(h);
  mean.resize(n);
  variance.resize(n);
  const int r = k / 2;
  const size_t ew = size_t(w) + size_t(k) - 1;
  auto at = [&](int x, int y) {
    return double(finite_dist(dist[size_t(std::clamp(y, 0, h - 1)) * size_t(w) +
                                   size_t(std::clamp(x, 0, w - 1))]));
  };
  fused_box(
      w, h, k, 2,
      [&](int y, double* ext) {
        // raw_moments' values of row y, extended by r clamped texels on each side.
        if (!slope_term) {
          moment_row(dist + size_t(y) * size_t(w), w, ext + r, ext + ew + size_t(r));
          extend_row(ext, w, r);
          extend_row(ext + ew, w, r);
          return;
        }
        for (int x = -r; x < w + r; ++x) {
          const double d = at(x, y);
          double m2 = d * d;
          const int xc = std::clamp(x, 0, w - 1);
          const double dx = min_diff(at(xc - 1, y), d, at(xc + 1, y));
          const double dy = min_diff(at(xc, y - 1), d, at(xc, y + 1));
          m2 += double(0.25 * (dx * dx + dy * dy));
          ext[size_t(x + r)] = d;
          ext[ew + size_t(x + r)] = m2;
        }
      },
      [&](size_t y, const double* out) {
        mean_variance_row(out, out + w, w, mean.data() + y * size_t(w),
                          variance.data() + y * size_t(w));
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

void filter_esm_log(const float* dist, int w, int h, int k, double c, std::vector<float>& out) {
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
  out.resize(n);
  const int r = k / 2;
  fused_box(
      w, h, k, 1,
      [&](int y, double* ext) {
        esm_exp_row(dist + size_t(y) * size_t(w), w, c, d_min, ext + r);
        extend_row(ext, w, r);
      },
      [&](size_t y, const double* filtered) {
        esm_log_row(filtered, w, c, d_min, out.data() + y * size_t(w));
      });
}

}  // namespace shadowlab
