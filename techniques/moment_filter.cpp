#include "techniques/moment_filter.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/cpu_features.h"
#include "core/prefetch.h"
#include "core/error.h"
#include "core/exp_log.h"
#include "core/parallel.h"
#include "core/simd_target.h"
#include "core/stream_copy.h"
#include "techniques/centred_window3.h"
#include "techniques/esm_float_tiles.h"
#include "techniques/texel_tiles.h"

namespace shadowlab {
namespace {

// The row kernels are compiled for AVX-512, AVX2 and baseline x86-64, picked at load time;
// element-wise IEEE arithmetic (no FMA: -ffp-contract=off) gives the same bits in every clone.
// clang 14 (the sanitizer and fuzz builds of CI) has no target_clones on templates: there the
// kernels are baseline only, which gives the same bits.
#if defined(__clang__)
#define SL_ROW_CLONES
#else
#define SL_ROW_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#endif

// Distance with "nothing seen" as the light's range: d < 1 ? d : 1.
inline float finite_dist(float d) { return d < 1.0f ? d : 1.0f; }

// finite_dist and v > 0 ? v : +0 as bit masks: the same values, but GCC if-converts (and so
// vectorizes) a ?: on doubles or floats only when AVX is on for the whole file, not in the
// target_clones kernels below; a compare turned into an integer mask is no control flow.
inline float finite_dist_bits(float d) {
  const uint32_t keep = uint32_t(0) - uint32_t(d < 1.0f);
  return std::bit_cast<float>((std::bit_cast<uint32_t>(d) & keep) |
                              (std::bit_cast<uint32_t>(1.0f) & ~keep));
}
inline double positive_part(double v) {
  const uint64_t keep = uint64_t(0) - uint64_t(v > 0.0);
  return std::bit_cast<double>(std::bit_cast<uint64_t>(v) & keep);
}

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

// The row loops of the fused separable box (fused_box below; filter_moments_double,
// filter_esm_log and filter_warped_moments): each input row's k-wide horizontal sums, then each
// output row's sum of its k rows. Every output is the same sequence of double additions as
// box_mean's two passes (left to right, then top to bottom, then × 1/k²); the loops run over x,
// which the compiler vectorizes without reordering any one texel's additions.

// out[x] = Σ_{i=0}^{k-1} ext[x + i], added in i order (ext: the row extended by k/2 clamped
// texels on each side).
template <class T>
SL_ROW_CLONES void hsum_row(const T* ext, int w, int k, T* out) {
  for (int x = 0; x < w; ++x) out[x] = T(0);
  for (int i = 0; i < k; ++i)
    for (int x = 0; x < w; ++x) out[x] += ext[x + i];
}

// dst[x] = (rows[0][x] + rows[1][x] + … + rows[k-1][x]) × inv, added in row order.
template <class T>
SL_ROW_CLONES void vsum_rows(const T* const* rows, int w, int k, T inv, T* dst) {
  for (int x = 0; x < w; ++x) dst[x] = rows[0][x];
  for (int j = 1; j < k; ++j)
    for (int x = 0; x < w; ++x) dst[x] += rows[j][x];
  for (int x = 0; x < w; ++x) dst[x] *= inv;
}

// Row r of raw_moments without the slope term: m1 = d, m2 = d² (d = finite_dist).
SL_ROW_CLONES void moment_row(const float* row, int w, double* m1, double* m2) {
  for (int x = 0; x < w; ++x) {
    const double d = double(finite_dist_bits(row[x]));
    m1[x] = d;
    m2[x] = d * d;
  }
}

// Mean and variance floats of filtered moment rows (filter_moments_double's storage).
SL_ROW_CLONES void mean_variance_row(const double* m1, const double* m2, int w, float* mean,
                                    float* var) {
  for (int x = 0; x < w; ++x) {
    mean[x] = float(m1[x]);
    const double v = m2[x] - m1[x] * m1[x];
    var[x] = float(positive_part(v));
  }
}

// The exp and log kernels a filter's rows use, chosen once per filter (core/cpu_features.h; a
// getenv per row would cost more than some rows): ESM's exp_wide16 and log_wide16 (AVX-512),
// exp_wide8 and log_wide8 (AVX2) or the scalar exp_wide and log_wide, EVSM's exp_f16, exp_f8 or
// exp_f, each set giving the same bits (core/exp_log.h). The
// oracles (fixed_kernels false) take the scalar ones, so the tests' comparisons of the two also
// compare the kernels bit for bit.
enum class ExpPath { scalar, avx2, avx512 };

ExpPath exp_path(bool fast) {
  if (!fast) return ExpPath::scalar;
  if (use_avx512_paths()) return ExpPath::avx512;
  return use_avx2_paths() ? ExpPath::avx2 : ExpPath::scalar;
}

// ESM's exponential of one row: out[x] = e^(c·(d − d_min)), d = finite_dist, by exp_wide of
// the exponent rounded once to float: c·(d − d_min) in double (d − d_min is exact there), then
// float. Why float precision is enough here: README "Techniques", ESM.
inline float esm_exponent(float d, double c, double d_min) {
  return float(c * (double(d) - d_min));
}
SL_ROW_CLONES void esm_exp_row_scalar(const float* row, int w, double c, double d_min,
                                      double* out) {
  for (int x = 0; x < w; ++x) out[x] = exp_wide(esm_exponent(finite_dist_bits(row[x]), c, d_min));
}

// EVSM's warped moments of one row: m1 = v = sign·e^(sign·c·(2d − 1)), m2 = v², the warp in
// float (exp_f of float(sign·c)·((d + d) − 1)), its moments and sums in double. Why float is
// exact enough for the warp: its rounding moves v by at most ~4e-6 relative (the argument's
// roundings, |x| <= 44.4, and exp_f's 2 ulp), which is what a change of d by 1–2 of its own
// float ulps does (dv/v = 2c·dd, c <= 44.4); the variance, whose cancellation needs double, is
// formed from the double sums as before (README "Techniques", EVSM).
SL_ROW_CLONES void warped_row_scalar(const float* row, int w, double c, double sign, double* m1,
                                     double* m2) {
  const float sc = float(sign * c);
  for (int x = 0; x < w; ++x) {
    const float d = finite_dist_bits(row[x]);
    const double v = sign * double(exp_f(sc * ((d + d) - 1.0f)));
    m1[x] = v;
    m2[x] = v * v;
  }
}

#if defined(__x86_64__)
// The same operations, 16 and 8 lanes at a time, the tail by the scalar rows. min(d, 1) is
// finite_dist (minps returns its second operand unless d < 1, NaN included); the exponents are
// formed in double 8 (4) at a time and rounded to float as esm_exponent does. The AVX-512
// conversions are the zero-masked forms for GCC 12's sake (core/exp_log.h's exp_d8).
SL_TARGET("avx512f") inline __m256 esm_exponent8(__m256 d, __m512d vc, __m512d vmin) {
  const __m512d dd = _mm512_maskz_cvtps_pd(0xFF, d);
  return _mm512_maskz_cvtpd_ps(0xFF, _mm512_mul_pd(vc, _mm512_sub_pd(dd, vmin)));
}

SL_TARGET("avx512f") void esm_exp_row_avx512(const float* row, int w, double c,
                                             double d_min, double* out) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m512d vc = _mm512_set1_pd(c), vmin = _mm512_set1_pd(d_min);
  int x = 0;
  for (; x + 16 <= w; x += 16) {
    const __m256 lo = esm_exponent8(_mm256_min_ps(_mm256_loadu_ps(row + x), one), vc, vmin);
    const __m256 hi = esm_exponent8(_mm256_min_ps(_mm256_loadu_ps(row + x + 8), one), vc, vmin);
    __m512d e_lo, e_hi;
    exp_wide16(join_ps(lo, hi), e_lo, e_hi);
    _mm512_storeu_pd(out + x, e_lo);
    _mm512_storeu_pd(out + x + 8, e_hi);
  }
  esm_exp_row_scalar(row + x, w - x, c, d_min, out + x);
}

SL_TARGET("avx2") inline __m128 esm_exponent4(__m128 d, __m256d vc, __m256d vmin) {
  return _mm256_cvtpd_ps(_mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(d), vmin)));
}

SL_TARGET("avx2") void esm_exp_row_avx2(const float* row, int w, double c,
                                        double d_min, double* out) {
  const __m128 one = _mm_set1_ps(1.0f);
  const __m256d vc = _mm256_set1_pd(c), vmin = _mm256_set1_pd(d_min);
  int x = 0;
  for (; x + 8 <= w; x += 8) {
    const __m128 lo = esm_exponent4(_mm_min_ps(_mm_loadu_ps(row + x), one), vc, vmin);
    const __m128 hi = esm_exponent4(_mm_min_ps(_mm_loadu_ps(row + x + 4), one), vc, vmin);
    __m256d e_lo, e_hi;
    exp_wide8(_mm256_set_m128(hi, lo), e_lo, e_hi);
    _mm256_storeu_pd(out + x, e_lo);
    _mm256_storeu_pd(out + x + 4, e_hi);
  }
  esm_exp_row_scalar(row + x, w - x, c, d_min, out + x);
}

// EVSM's warp alone, as floats: v[x] = sign·exp_f(float(sign·c)·((d + d) − 1)), the value
// warped_row_scalar forms (its v is that float, widened; sign = ±1, so the product is exact).
// The fixed-width path sums these floats' moments by hsum_moments_k (v and v² formed in double
// there, as VSM's are), so the row kernel writes 4 bytes per texel instead of two doubles' 16.
// 16 (AVX-512) and 8 (AVX2) floats at a time by exp_f16 / exp_f8; min(d, 1) is finite_dist as
// above; the tail by the scalar loop.
SL_ROW_CLONES void warp_row_f_scalar(const float* row, int w, double c, double sign, float* v) {
  const float sc = float(sign * c), fs = float(sign);
  for (int x = 0; x < w; ++x) {
    const float d = finite_dist_bits(row[x]);
    v[x] = fs * exp_f(sc * ((d + d) - 1.0f));
  }
}

SL_TARGET("avx512f") void warp_row_f_avx512(const float* row, int w, double c,
                                            double sign, float* v) {
  const __m512 one = _mm512_set1_ps(1.0f), sc = _mm512_set1_ps(float(sign * c));
  const __m512 fs = _mm512_set1_ps(float(sign));
  int x = 0;
  for (; x + 16 <= w; x += 16) {
    // (Zero-masked forms with every lane on, for GCC 12's -Wmaybe-uninitialized: exp_d8.)
    const __m512 d = _mm512_maskz_min_ps(0xFFFF, _mm512_loadu_ps(row + x), one);
    const __m512 e = exp_f16(_mm512_mul_ps(sc, _mm512_sub_ps(_mm512_add_ps(d, d), one)));
    _mm512_storeu_ps(v + x, _mm512_mul_ps(fs, e));
  }
  warp_row_f_scalar(row + x, w - x, c, sign, v + x);
}

SL_TARGET("avx2") void warp_row_f_avx2(const float* row, int w, double c,
                                       double sign, float* v) {
  const __m256 one = _mm256_set1_ps(1.0f), sc = _mm256_set1_ps(float(sign * c));
  const __m256 fs = _mm256_set1_ps(float(sign));
  int x = 0;
  for (; x + 8 <= w; x += 8) {
    const __m256 d = _mm256_min_ps(_mm256_loadu_ps(row + x), one);
    const __m256 e = exp_f8(_mm256_mul_ps(sc, _mm256_sub_ps(_mm256_add_ps(d, d), one)));
    _mm256_storeu_ps(v + x, _mm256_mul_ps(fs, e));
  }
  warp_row_f_scalar(row + x, w - x, c, sign, v + x);
}
#endif

void esm_exp_row(ExpPath path, const float* row, int w, double c, double d_min, double* out) {
#if defined(__x86_64__)
  if (path == ExpPath::avx512) return esm_exp_row_avx512(row, w, c, d_min, out);
  if (path == ExpPath::avx2) return esm_exp_row_avx2(row, w, c, d_min, out);
#endif
  esm_exp_row_scalar(row, w, c, d_min, out);
}

void warp_row_f(ExpPath path, const float* row, int w, double c, double sign, float* v) {
#if defined(__x86_64__)
  if (path == ExpPath::avx512) return warp_row_f_avx512(row, w, c, sign, v);
  if (path == ExpPath::avx2) return warp_row_f_avx2(row, w, c, sign, v);
#endif
  warp_row_f_scalar(row, w, c, sign, v);
}

// MSM's power moments of one row, in float (moment_filter.h says why): p[0..3][x] = d, d²,
// d³ = d²·d, d⁴ = d²·d² (d = finite_dist), each plane at its own offset `stride` from the last.
SL_ROW_CLONES void power_row(const float* row, int w, size_t stride, float* p) {
  for (int x = 0; x < w; ++x) p[x] = finite_dist_bits(row[x]);
  for (int x = 0; x < w; ++x) {
    const float d = p[x], d2 = d * d;
    p[stride + size_t(x)] = d2;
    p[2 * stride + size_t(x)] = d2 * d;
    p[3 * stride + size_t(x)] = d2 * d2;
  }
}

// ESM's occluder term of one filtered row: c·d_min + ln(filtered).
SL_ROW_CLONES void esm_log_row(const double* filtered, int w, double c, double d_min,
                              float* out) {
  for (int x = 0; x < w; ++x) out[x] = float(c * d_min + log_wide(filtered[x]));
}

// Output columns [x0, x0 + n) of a row and the input columns their k-wide windows read:
// [in0, in0 + in_n) of the image (clipped to it), placed at ext[lead ..] of the extended row,
// whose positions before lead and from lead + in_n on repeat the image's edge texels (clamp to
// edge). The whole row: x0 = 0, n = w, in0 = 0, in_n = w, lead = k/2.
struct SpanCols {
  int x0, n, in0, in_n, lead;
};

SpanCols span_cols(const TexelSpan& s, int w, int r) {
  SpanCols c;
  c.x0 = s.x0;
  c.n = s.x1 - s.x0;
  c.in0 = std::max(0, s.x0 - r);
  c.in_n = std::min(w, s.x1 + r) - c.in0;
  c.lead = c.in0 - (s.x0 - r);
  return c;
}

// Fills the clamped positions of a span's extended row (n + k − 1 values) from its edge values.
template <class T>
inline void extend_span(T* ext, const SpanCols& c, int k) {
  for (int i = 0; i < c.lead; ++i) ext[i] = ext[c.lead];
  const int end = c.lead + c.in_n, total = c.n + k - 1;
  for (int i = end; i < total; ++i) ext[i] = ext[end - 1];
}

// Kernels for the common box widths with k a compile-time constant, so each x iteration keeps
// its k-term sums in registers instead of re-reading and re-storing whole rows (the runtime-k
// loops above, kept for other widths and the slope term). The additions are the same, in the
// same order: a sum starts from 0.0 (as the runtime-k hsum_row does) and adds left to right,
// rows top to bottom, then × 1/k²; so either path gives the other's bits.

// VSM: h1[x] = Σ_i d, h2[x] = Σ_i d² over ext[x .. x + K − 1] (ext: the clamped finite row).
template <int K>
SL_ROW_CLONES void hsum_moments_k(const float* ext, int w, double* h1, double* h2) {
  for (int x = 0; x < w; ++x) {
    double s1 = 0.0, s2 = 0.0;
    for (int i = 0; i < K; ++i) {
      const double d = double(ext[x + i]);
      s1 += d;
      s2 += d * d;
    }
    h1[x] = s1;
    h2[x] = s2;
  }
}

// VSM: the K rows of both planes summed, × inv, stored as mean and variance floats.
template <int K>
SL_ROW_CLONES void vsm_out_k(const double* const* rows, int w, double inv, float* mean,
                             float* var) {
  const double* r1[K];
  const double* r2[K];
  for (int j = 0; j < K; ++j) {
    r1[j] = rows[j];
    r2[j] = rows[K + j];
  }
  for (int x = 0; x < w; ++x) {
    double a = r1[0][x], b = r2[0][x];
    for (int j = 1; j < K; ++j) {
      a += r1[j][x];
      b += r2[j][x];
    }
    a *= inv;
    b *= inv;
    mean[x] = float(a);
    const double v = b - a * a;
    var[x] = float(positive_part(v));
  }
}

// out[2x] = a[x], out[2x + 1] = b[x]: two rows into one interleaved row (a zip the compiler
// vectorizes; the strided stores of writing the interleaved row directly did not, and made the
// VSM filter ~25 % slower).
// Texels to write one by one before out + S·x starts a 64-byte line (S floats per texel), so the
// vector stores after them do not straddle cache lines: large vectors' storage is 16-byte
// aligned here (glibc's mmap chunks), and a 64-byte store across two lines costs about two.
// A row whose texels never start a line returns `unreachable`: 0 for ordinary stores (they may
// straddle), w where the stores need aligned addresses (then every texel goes one by one).
inline int texels_to_line(const float* out, int floats_per_texel, int w, int unreachable = 0) {
  const uintptr_t bytes = (64 - (reinterpret_cast<uintptr_t>(out) & 63)) & 63;
  const uintptr_t texel_bytes = uintptr_t(floats_per_texel) * 4;
  if (bytes % texel_bytes != 0) return unreachable;
  return std::min(w, int(bytes / texel_bytes));
}

// out[4x + c] = rows[c·w + x] for c = 0..3: four rows into one interleaved row.
SL_ROW_CLONES void interleave4_row(const float* rows, int w, float* out) {
  const int head = texels_to_line(out, 4, w);
  for (int x = 0; x < head; ++x)
    for (int c = 0; c < 4; ++c) out[4 * x + c] = rows[size_t(c) * size_t(w) + size_t(x)];
  for (int x = head; x < w; ++x)
    for (int c = 0; c < 4; ++c) out[4 * x + c] = rows[size_t(c) * size_t(w) + size_t(x)];
}

SL_ROW_CLONES void interleave_row(const float* a, const float* b, int w, float* out) {
  const int head = texels_to_line(out, 2, w);
  for (int x = 0; x < head; ++x) {
    out[2 * x] = a[x];
    out[2 * x + 1] = b[x];
  }
  for (int x = head; x < w; ++x) {
    out[2 * x] = a[x];
    out[2 * x + 1] = b[x];
  }
}

// One texel of hsum_powers_k: the four sums at x (also the fused AVX2 row's heads and tails).
template <int K>
inline void hsum_powers_texel(const float* ext, int x, float* const* h) {
  float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f, s3 = 0.0f;
  for (int i = 0; i < K; ++i) {
    const float d = ext[x + i], d2 = d * d;
    s0 += d;
    s1 += d2;
    s2 += d2 * d;
    s3 += d2 * d2;
  }
  h[0][x] = s0;
  h[1][x] = s1;
  h[2][x] = s2;
  h[3][x] = s3;
}

// MSM: h_c[x] = Σ_i d^(c+1) over ext[x .. x + K − 1] (ext: the clamped finite row), the powers
// formed as power_row forms them (d² = d·d, d³ = d²·d, d⁴ = d²·d²) and each sum started from 0
// and added in i order: hsum_k's sums of power_row's planes, without writing the planes.
template <int K>
SL_ROW_CLONES void hsum_powers_k(const float* ext, int w, float* h0, float* h1, float* h2,
                                 float* h3) {
  float* const h[4] = {h0, h1, h2, h3};
  for (int x = 0; x < w; ++x) hsum_powers_texel<K>(ext, x, h);
}

// ESM: h[x] = Σ_i ext[x + i] (ext: the row's exponentials, extended).
template <int K>
SL_ROW_CLONES void hsum_k(const double* ext, int w, double* h) {
  for (int x = 0; x < w; ++x) {
    double s = 0.0;
    for (int i = 0; i < K; ++i) s += ext[x + i];
    h[x] = s;
  }
}

// ESM: the K rows summed, × inv, then c·d_min + ln(·) as float.
template <int K>
SL_ROW_CLONES void esm_out_k_scalar(const double* const* rows, int w, double inv, double c,
                                    double d_min, float* out) {
  const double* r[K];
  for (int j = 0; j < K; ++j) r[j] = rows[j];
  for (int x = 0; x < w; ++x) {
    double a = r[0][x];
    for (int j = 1; j < K; ++j) a += r[j][x];
    a *= inv;
    out[x] = float(c * d_min + log_wide(a));
  }
}

#if defined(__x86_64__)
// The same sums and log_wide16 / log_wide8 (core/exp_log.h), 16 and 8 lanes at a time; the
// tail by the scalar kernel. The AVX-512 conversions are the zero-masked forms (as in
// esm_exp_row_avx512).
template <int K>
SL_TARGET("avx512f") inline __m512d esm_window8(const double* const* r, int x, __m512d vinv) {
  __m512d a = _mm512_loadu_pd(r[0] + x);
  for (int j = 1; j < K; ++j) a = _mm512_add_pd(a, _mm512_loadu_pd(r[j] + x));
  return _mm512_mul_pd(a, vinv);
}

template <int K>
SL_TARGET("avx512f") void esm_out_k_avx512(const double* const* rows, int w,
                                           double inv, double c, double d_min,
                                           float* out) {
  const double* r[K];
  for (int j = 0; j < K; ++j) r[j] = rows[j];
  const __m512d vinv = _mm512_set1_pd(inv), cd = _mm512_set1_pd(c * d_min);
  int x = 0;
  for (; x + 16 <= w; x += 16) {
    __m512d lo, hi;
    log_wide16(esm_window8<K>(r, x, vinv), esm_window8<K>(r, x + 8, vinv), lo, hi);
    _mm256_storeu_ps(out + x, _mm512_maskz_cvtpd_ps(0xFF, _mm512_add_pd(cd, lo)));
    _mm256_storeu_ps(out + x + 8, _mm512_maskz_cvtpd_ps(0xFF, _mm512_add_pd(cd, hi)));
  }
  for (int j = 0; j < K; ++j) r[j] += x;
  esm_out_k_scalar<K>(r, w - x, inv, c, d_min, out + x);
}

template <int K>
SL_TARGET("avx2") inline __m256d esm_window4(const double* const* r, int x, __m256d vinv) {
  __m256d a = _mm256_loadu_pd(r[0] + x);
  for (int j = 1; j < K; ++j) a = _mm256_add_pd(a, _mm256_loadu_pd(r[j] + x));
  return _mm256_mul_pd(a, vinv);
}

template <int K>
SL_TARGET("avx2") void esm_out_k_avx2(const double* const* rows, int w,
                                      double inv, double c, double d_min,
                                      float* out) {
  const double* r[K];
  for (int j = 0; j < K; ++j) r[j] = rows[j];
  const __m256d vinv = _mm256_set1_pd(inv), cd = _mm256_set1_pd(c * d_min);
  int x = 0;
  for (; x + 8 <= w; x += 8) {
    __m256d lo, hi;
    log_wide8(esm_window4<K>(r, x, vinv), esm_window4<K>(r, x + 4, vinv), lo, hi);
    _mm_storeu_ps(out + x, _mm256_cvtpd_ps(_mm256_add_pd(cd, lo)));
    _mm_storeu_ps(out + x + 4, _mm256_cvtpd_ps(_mm256_add_pd(cd, hi)));
  }
  for (int j = 0; j < K; ++j) r[j] += x;
  esm_out_k_scalar<K>(r, w - x, inv, c, d_min, out + x);
}
#endif

template <int K>
void esm_out_k(ExpPath path, const double* const* rows, int w, double inv, double c,
               double d_min, float* out) {
#if defined(__x86_64__)
  if (path == ExpPath::avx512) return esm_out_k_avx512<K>(rows, w, inv, c, d_min, out);
  if (path == ExpPath::avx2) return esm_out_k_avx2<K>(rows, w, inv, c, d_min, out);
#endif
  esm_out_k_scalar<K>(rows, w, inv, c, d_min, out);
}

// MSM: one plane's K rows summed in float, × inv.
template <int K>
SL_ROW_CLONES void mean_out_k(const float* const* rows, int w, float inv, float* out) {
  const float* r[K];
  for (int j = 0; j < K; ++j) r[j] = rows[j];
  for (int x = 0; x < w; ++x) {
    float a = r[0][x];
    for (int j = 1; j < K; ++j) a += r[j][x];
    out[x] = a * inv;
  }
}

#if defined(__x86_64__)
// rows[0][x] + rows[1][x] + … + rows[K − 1][x], added in row order (mean_out_k's sum), for one
// texel and for 8 (AVX-512): the output kernels' sums of K filtered rows.
template <int K>
inline double sum_rows(const double* const* rows, int x) {
  double a = rows[0][x];
  for (int j = 1; j < K; ++j) a += rows[j][x];
  return a;
}
// One texel of the fused output rows, for their heads and tails (the vector steps' operations):
// VSM's (mean, variance) from rows[0 .. K − 1] and rows[K .. 2K − 1]; MSM's four means from
// plane c's rows[c·K .. c·K + K − 1], summed in float.
template <int K>
inline void vsm_out_texel(const double* const* rows, int x, double inv, float* out) {
  const double a = sum_rows<K>(rows, x) * inv, b = sum_rows<K>(rows + K, x) * inv;
  out[2 * x] = float(a);
  out[2 * x + 1] = float(positive_part(b - a * a));
}
template <int K>
inline void msm_out_texel(const float* const* rows, int x, float inv, float* out) {
  for (int c = 0; c < 4; ++c) {
    float a = rows[c * K][x];
    for (int j = 1; j < K; ++j) a += rows[c * K + j][x];
    out[4 * x + c] = a * inv;
  }
}
template <int K>
SL_TARGET("avx512f") inline __m512d sum_rows8(const double* const* rows, int x) {
  __m512d a = _mm512_loadu_pd(rows[0] + x);
  for (int j = 1; j < K; ++j) a = _mm512_add_pd(a, _mm512_loadu_pd(rows[j] + x));
  return a;
}

// VSM's (and EVSM's two-value) output row straight into the interleaved plane: vsm_out_k's sums,
// products and positive part for both planes (rows[0 .. K − 1] the first moments', rows[K ..
// 2K − 1] the second's), 8 texels at a time, zipped to (mean, variance) per texel and stored as
// one 64-byte line per 8 texels with ordinary stores (VSM keeps its map in the caches for the
// lookup: README "Technique benchmark"). What vsm_out_k into scratch and interleave_row did in
// two passes, in one; the same bits (MomentFilter.FixedWidthKernelsEqualTheRuntimeWidthLoops-
// BitForBit). Texels before the first line and after the last whole 8 go one by one.
template <int K>
SL_TARGET("avx512f") void vsm_out_interleaved_avx512(const double* const* rows,
                                                     int w, double inv,
                                                     float* out) {
  const int head = texels_to_line(out, 2, w);
  int x = 0;
  for (; x < head; ++x) vsm_out_texel<K>(rows, x, inv, out);
  const __m512d vinv = _mm512_set1_pd(inv), zero = _mm512_setzero_pd();
  for (; x + 8 <= w; x += 8) {
    const __m512d a = _mm512_mul_pd(sum_rows8<K>(rows, x), vinv);
    const __m512d b = _mm512_mul_pd(sum_rows8<K>(rows + K, x), vinv);
    const __m512d v = _mm512_sub_pd(b, _mm512_mul_pd(a, a));
    // positive_part: v where v > 0, else +0 (a NaN too).
    const __m512d pv = _mm512_mask_mov_pd(zero, _mm512_cmp_pd_mask(v, zero, _CMP_GT_OQ), v);
    const __m256 mean = _mm512_maskz_cvtpd_ps(0xFF, a), var = _mm512_maskz_cvtpd_ps(0xFF, pv);
    const __m256 lo = _mm256_unpacklo_ps(mean, var);  // texels 0 1 | 4 5
    const __m256 hi = _mm256_unpackhi_ps(mean, var);  // texels 2 3 | 6 7
    _mm256_storeu_ps(out + 2 * x, _mm256_permute2f128_ps(lo, hi, 0x20));
    _mm256_storeu_ps(out + 2 * x + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
  }
  for (; x < w; ++x) vsm_out_texel<K>(rows, x, inv, out);
}

// The same in AVX2, 4 texels (one 32-byte store) per step: the AVX2-only machines' fused row
// (before it, their rows went through vsm_out_k into scratch and interleave_row, two passes).
template <int K>
SL_TARGET("avx2") void vsm_out_interleaved_avx2(const double* const* rows, int w,
                                                double inv, float* out) {
  const int head = texels_to_line(out, 2, w);
  int x = 0;
  for (; x < head; ++x) vsm_out_texel<K>(rows, x, inv, out);
  const double* r[2 * K];
  for (int j = 0; j < 2 * K; ++j) r[j] = rows[j];
  const __m256d vinv = _mm256_set1_pd(inv), zero = _mm256_setzero_pd();
  for (; x + 4 <= w; x += 4) {
    __m256d a = _mm256_loadu_pd(r[0] + x), b = _mm256_loadu_pd(r[K] + x);
    for (int j = 1; j < K; ++j) {
      a = _mm256_add_pd(a, _mm256_loadu_pd(r[j] + x));
      b = _mm256_add_pd(b, _mm256_loadu_pd(r[K + j] + x));
    }
    a = _mm256_mul_pd(a, vinv);
    b = _mm256_mul_pd(b, vinv);
    const __m256d v = _mm256_sub_pd(b, _mm256_mul_pd(a, a));
    // positive_part: v where v > 0, else +0 (a NaN too).
    const __m256d pv = _mm256_and_pd(v, _mm256_cmp_pd(v, zero, _CMP_GT_OQ));
    const __m128 mean = _mm256_cvtpd_ps(a), var = _mm256_cvtpd_ps(pv);
    // texels 0 1 in the low half, 2 3 in the high one.
    _mm256_storeu_ps(out + 2 * x,
                     _mm256_set_m128(_mm_unpackhi_ps(mean, var), _mm_unpacklo_ps(mean, var)));
  }
  for (; x < w; ++x) vsm_out_texel<K>(rows, x, inv, out);
}
#endif

#if defined(__x86_64__)
// Four planes' 16 texels (m[c]: plane c, texels x .. x + 15) transposed to (m1 m2 m3 m4) per
// texel: line[q] holds texels 4q .. 4q + 3, the q-th 64 bytes of the interleaved row.
SL_TARGET("avx512f") inline void transpose4_avx512(const __m512* m, __m512* line) {
  // Within each 128-bit lane (texels 4q .. 4q + 3): t0, t1 planes 0 1 interleaved, t2, t3
  // planes 2 3; u_i texel 4q + i's four moments in lane q.
  // (The zero-masked forms with every lane on: GCC 12's unmasked ones trip
  // -Wmaybe-uninitialized, as in core/exp_log.h.)
  const __m512 t0 = _mm512_maskz_unpacklo_ps(0xFFFF, m[0], m[1]);
  const __m512 t1 = _mm512_maskz_unpackhi_ps(0xFFFF, m[0], m[1]);
  const __m512 t2 = _mm512_maskz_unpacklo_ps(0xFFFF, m[2], m[3]);
  const __m512 t3 = _mm512_maskz_unpackhi_ps(0xFFFF, m[2], m[3]);
  const __m512 u0 = _mm512_maskz_shuffle_ps(0xFFFF, t0, t2, 0x44);
  const __m512 u1 = _mm512_maskz_shuffle_ps(0xFFFF, t0, t2, 0xEE);
  const __m512 u2 = _mm512_maskz_shuffle_ps(0xFFFF, t1, t3, 0x44);
  const __m512 u3 = _mm512_maskz_shuffle_ps(0xFFFF, t1, t3, 0xEE);
  // Lanes regrouped: v0 = texels 0 4 1 5, v1 = 2 6 3 7, v2 = 8 12 9 13, v3 = 10 14 11 15.
  const __m512 v0 = _mm512_maskz_shuffle_f32x4(0xFFFF, u0, u1, 0x44);
  const __m512 v1 = _mm512_maskz_shuffle_f32x4(0xFFFF, u2, u3, 0x44);
  const __m512 v2 = _mm512_maskz_shuffle_f32x4(0xFFFF, u0, u1, 0xEE);
  const __m512 v3 = _mm512_maskz_shuffle_f32x4(0xFFFF, u2, u3, 0xEE);
  line[0] = _mm512_maskz_shuffle_f32x4(0xFFFF, v0, v1, 0x88);  // texels 0–3
  line[1] = _mm512_maskz_shuffle_f32x4(0xFFFF, v0, v1, 0xDD);  // 4–7
  line[2] = _mm512_maskz_shuffle_f32x4(0xFFFF, v2, v3, 0x88);  // 8–11
  line[3] = _mm512_maskz_shuffle_f32x4(0xFFFF, v2, v3, 0xDD);  // 12–15
}

// The transposed 16 texels written as four 64-byte lines at out (64-byte aligned) with
// non-temporal stores.
SL_TARGET("avx512f") inline void stream_transposed4_avx512(const __m512* m, float* out) {
  __m512 line[4];
  transpose4_avx512(m, line);
  for (int q = 0; q < 4; ++q) _mm512_stream_ps(out + 16 * q, line[q]);
}

// MSM's four planes' output row straight into the interleaved map: mean_out_k's float sums and
// products for planes c = 0..3 (rows[c·K .. c·K + K − 1]), 16 texels at a time, transposed to
// (m1 m2 m3 m4) per texel and written as four 64-byte lines with non-temporal stores (as
// core/stream_copy.h writes them; the caller's fused_box fences). What mean_out_k,
// interleave4_row and the stream copy do in three passes over tmp rows, in one; the same bits
// (tests: MomentFilter.FixedWidthKernelsEqualTheRuntimeWidthLoopsBitForBit). Texels before the
// first 64-byte line and after the last whole 16 go one by one in the same operations.
template <int K>
SL_TARGET("avx512f") void msm_out_interleaved_avx512(const float* const* rows,
                                                     int w, float inv,
                                                     float* out) {
  // Non-temporal stores need aligned addresses: a row that cannot reach a line on a texel
  // boundary (never for the map's 16-byte aligned storage) goes one texel at a time.
  const int head = texels_to_line(out, 4, w, w);
  int x = 0;
  for (; x < head; ++x) msm_out_texel<K>(rows, x, inv, out);
  // The row pointers in locals: through `rows` they would be reloaded after every store.
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m512 vinv = _mm512_set1_ps(inv);
  for (; x + 16 <= w; x += 16) {
    __m512 m[4];
    for (int c = 0; c < 4; ++c) {
      __m512 a = _mm512_loadu_ps(r[c * K] + x);
      for (int j = 1; j < K; ++j) a = _mm512_add_ps(a, _mm512_loadu_ps(r[c * K + j] + x));
      m[c] = _mm512_mul_ps(a, vinv);
    }
    stream_transposed4_avx512(m, out + 4 * x);
  }
  for (; x < w; ++x) msm_out_texel<K>(rows, x, inv, out);
}

// 16 floats at p, or (Partial) the lanes in `lanes` with the others zero and unread.
template <bool Partial>
SL_TARGET("avx512f") inline __m512 load16(__mmask16 lanes, const float* p) {
  if constexpr (Partial) return _mm512_maskz_loadu_ps(lanes, p);
  else return _mm512_loadu_ps(p);
}

// The four window means of texels x .. x + 15 for msm_hsum_out_avx512 (m[c]: plane c), the
// window's new bottom row's sums stored into h[c] + x on the way; or (Partial) the lanes in
// `lanes` only, by masked loads (which read nothing past a row's end) and masked stores. The
// lanes left out compute on zeros and are never stored, so each texel gets the same operations
// whichever step it falls in.
template <int K, bool Partial>
SL_TARGET("avx512f") inline void msm_hsum_means16(const float* ext, float* const* h,
                                                  const float* const* r, int x, __mmask16 lanes,
                                                  __m512 vinv, __m512* m) {
  __m512 s[4] = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_ps(),
                 _mm512_setzero_ps()};
  for (int i = 0; i < K; ++i) {
    const __m512 d = load16<Partial>(lanes, ext + x + i), d2 = _mm512_mul_ps(d, d);
    s[0] = _mm512_add_ps(s[0], d);
    s[1] = _mm512_add_ps(s[1], d2);
    s[2] = _mm512_add_ps(s[2], _mm512_mul_ps(d2, d));
    s[3] = _mm512_add_ps(s[3], _mm512_mul_ps(d2, d2));
  }
  for (int c = 0; c < 4; ++c) {
    if constexpr (Partial) _mm512_mask_storeu_ps(h[c] + x, lanes, s[c]);
    else _mm512_storeu_ps(h[c] + x, s[c]);
    __m512 a = s[c];
    if constexpr (K > 1) {
      a = load16<Partial>(lanes, r[c * K] + x);
      for (int j = 1; j < K - 1; ++j)
        a = _mm512_add_ps(a, load16<Partial>(lanes, r[c * K + j] + x));
      a = _mm512_add_ps(a, s[c]);
    }
    m[c] = _mm512_mul_ps(a, vinv);
  }
}

// One 64-byte line of an interleaved output row (4 texels, first texel t0, which may lie before
// the row: t0 < 0) at `line`: a non-temporal store when all four texels are in [0, n), else a
// masked ordinary store of those that are (the rest of the line belongs to other texels).
SL_TARGET("avx512f") inline void store_line4(float* line, int t0, int n, __m512 v) {
  const int lo = std::max(t0, 0), hi = std::min(t0 + 4, n);
  if (lo == t0 && hi == t0 + 4) {
    _mm512_stream_ps(line, v);
  } else if (lo < hi) {
    const unsigned bits = ((1u << (4 * (hi - t0))) - 1u) & ~((1u << (4 * (lo - t0))) - 1u);
    _mm512_mask_storeu_ps(line, __mmask16(bits), v);
  }
}

// msm_hsum_out_avx512 for an output row whose texel 0 lies S texels (16·S bytes) past a 64-byte
// line. The steps run at x = 0, 16, 32, …, so the ring's rows (64-byte aligned, fused_box) are
// read and written on whole lines; output line j (texels 4j − S ..
// 4j − S + 3) is the last S texels of one transposed line and the first 4 − S of the next, one
// valignd, and goes out whole (non-temporal) except at the row's two ends (store_line4).
template <int K, int S>
SL_TARGET("avx512f") void msm_hsum_out_lines(const float* ext, float* const* h,
                                             const float* const* r, int w, __m512 vinv,
                                             float* out) {
  // Line j starts at texel 4j − S's address (16 bytes a texel). Addresses are formed as
  // integers: line 0 may begin before the map's storage (its lanes there are never stored).
  const uintptr_t line0 = reinterpret_cast<uintptr_t>(out) - uintptr_t(16 * S);
  auto line_at = [&](int t0) {  // t0 + S: a multiple of 4
    return reinterpret_cast<float*>(line0 + uintptr_t(16 * (t0 + S)));
  };
  __m512 prev = _mm512_setzero_ps();  // the previous step's texels x − 4 .. x − 1
  int x = 0;
  for (; x < w; x += 16) {
    __m512 m[4];
    if (x + 16 <= w) {
      msm_hsum_means16<K, false>(ext, h, r, x, __mmask16(0xFFFF), vinv, m);
    } else {
      msm_hsum_means16<K, true>(ext, h, r, x, __mmask16((1u << (w - x)) - 1u), vinv, m);
    }
    __m512 line[4];
    transpose4_avx512(m, line);
    for (int q = 0; q < 4; ++q) {
      const int t0 = x + 4 * q - S;
      if constexpr (S == 0) {
        store_line4(line_at(t0), t0, w, line[q]);
      } else {
        // Texels t0 .. t0 + S − 1 from the transposed line before, the rest from line q.
        const __m512 lo = q == 0 ? prev : line[q - 1];
        const __m512 v = _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(
            0xFFFF, _mm512_castps_si512(line[q]), _mm512_castps_si512(lo), 16 - 4 * S));
        store_line4(line_at(t0), t0, w, v);
      }
    }
    prev = line[3];
  }
  if constexpr (S != 0) {
    // The line after the last step's: its first S texels (from the last transposed line).
    const int t0 = x - S;
    const __m512 v = _mm512_castsi512_ps(_mm512_maskz_alignr_epi32(
        0xFFFF, _mm512_setzero_si512(), _mm512_castps_si512(prev), 16 - 4 * S));
    store_line4(line_at(t0), t0, w, v);
  }
}

// hsum_powers_k for the window's new bottom row (its sums into h[0..3]) and
// msm_out_interleaved_avx512 for the output row above it, in one pass of 16 texels at a time:
// rows[c·K + K − 1] is h[c], the K − 1 rows above it are read as before, and the new sums are
// added last from registers (the row order of mean_out_k). The same operations, so the same
// bits (MomentFilter.FixedWidthKernelsEqualTheRuntimeWidthLoopsBitForBit). Why one pass: the
// output's non-temporal stores (16 B a texel, ~35 MB a cube on the default scene) had a pass of
// their own while the row sums' pass wrote nothing; here the arithmetic can run while they drain
// (~8 % off the cube filter on Zen 5: README "Technique benchmark", seventeenth session).
template <int K>
SL_TARGET("avx512f") void msm_hsum_out_avx512(const float* ext, float* const* h,
                                              const float* const* rows, int w, float inv,
                                              float* out) {
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m512 vinv = _mm512_set1_ps(inv);
  // The map's storage is 16-byte aligned (glibc's), so texel 0 lies 0 to 3 texels past a line;
  // storage that is not (never seen) goes one texel at a time.
  const uintptr_t a = reinterpret_cast<uintptr_t>(out);
  if (a % 16 != 0) {
    for (int x = 0; x < w; ++x) {
      hsum_powers_texel<K>(ext, x, h);
      msm_out_texel<K>(rows, x, inv, out);
    }
    return;
  }
  switch ((a / 16) % 4) {
    case 0: msm_hsum_out_lines<K, 0>(ext, h, r, w, vinv, out); break;
    case 1: msm_hsum_out_lines<K, 1>(ext, h, r, w, vinv, out); break;
    case 2: msm_hsum_out_lines<K, 2>(ext, h, r, w, vinv, out); break;
    default: msm_hsum_out_lines<K, 3>(ext, h, r, w, vinv, out); break;
  }
}

// The AVX2 form of stream_transposed4_avx512: 8 texels, two 64-byte lines.
SL_TARGET("avx2") inline void stream_transposed4_avx2(const __m256* m, float* out) {
  // Within each 128-bit half (texels 4q .. 4q + 3): t0, t1 planes 0 1 interleaved, t2, t3
  // planes 2 3; u_i texel i's four moments in the low half, texel 4 + i's in the high one.
  const __m256 t0 = _mm256_unpacklo_ps(m[0], m[1]), t1 = _mm256_unpackhi_ps(m[0], m[1]);
  const __m256 t2 = _mm256_unpacklo_ps(m[2], m[3]), t3 = _mm256_unpackhi_ps(m[2], m[3]);
  const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
  const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
  _mm256_stream_ps(out, _mm256_permute2f128_ps(u0, u1, 0x20));       // texels 0 1
  _mm256_stream_ps(out + 8, _mm256_permute2f128_ps(u2, u3, 0x20));   // 2 3
  _mm256_stream_ps(out + 16, _mm256_permute2f128_ps(u0, u1, 0x31));  // 4 5
  _mm256_stream_ps(out + 24, _mm256_permute2f128_ps(u2, u3, 0x31));  // 6 7
}

// The same in AVX2, 8 texels (one 4 × 8 transpose, two 64-byte lines of streamed stores) per
// step: the AVX2-only machines' fused row (before it: mean_out_k into tmp rows,
// interleave4_row and the stream copy, three passes).
template <int K>
SL_TARGET("avx2") void msm_out_interleaved_avx2(const float* const* rows, int w,
                                                float inv, float* out) {
  const int head = texels_to_line(out, 4, w, w);
  int x = 0;
  for (; x < head; ++x) msm_out_texel<K>(rows, x, inv, out);
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m256 vinv = _mm256_set1_ps(inv);
  for (; x + 8 <= w; x += 8) {
    __m256 m[4];
    for (int c = 0; c < 4; ++c) {
      __m256 a = _mm256_loadu_ps(r[c * K] + x);
      for (int j = 1; j < K; ++j) a = _mm256_add_ps(a, _mm256_loadu_ps(r[c * K + j] + x));
      m[c] = _mm256_mul_ps(a, vinv);
    }
    stream_transposed4_avx2(m, out + 4 * x);
  }
  for (; x < w; ++x) msm_out_texel<K>(rows, x, inv, out);
}

// msm_hsum_out_avx512 in AVX2, 8 texels a step.
template <int K>
SL_TARGET("avx2") void msm_hsum_out_avx2(const float* ext, float* const* h,
                                         const float* const* rows, int w, float inv,
                                         float* out) {
  const int head = texels_to_line(out, 4, w, w);
  int x = 0;
  for (; x < head; ++x) {
    hsum_powers_texel<K>(ext, x, h);
    msm_out_texel<K>(rows, x, inv, out);
  }
  const float* r[4 * K];
  for (int j = 0; j < 4 * K; ++j) r[j] = rows[j];
  const __m256 vinv = _mm256_set1_ps(inv);
  for (; x + 8 <= w; x += 8) {
    __m256 s[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(),
                   _mm256_setzero_ps()};
    for (int i = 0; i < K; ++i) {
      const __m256 d = _mm256_loadu_ps(ext + x + i), d2 = _mm256_mul_ps(d, d);
      s[0] = _mm256_add_ps(s[0], d);
      s[1] = _mm256_add_ps(s[1], d2);
      s[2] = _mm256_add_ps(s[2], _mm256_mul_ps(d2, d));
      s[3] = _mm256_add_ps(s[3], _mm256_mul_ps(d2, d2));
    }
    __m256 m[4];
    for (int c = 0; c < 4; ++c) {
      _mm256_storeu_ps(h[c] + x, s[c]);
      __m256 a = s[c];
      if constexpr (K > 1) {
        a = _mm256_loadu_ps(r[c * K] + x);
        for (int j = 1; j < K - 1; ++j) a = _mm256_add_ps(a, _mm256_loadu_ps(r[c * K + j] + x));
        a = _mm256_add_ps(a, s[c]);
      }
      m[c] = _mm256_mul_ps(a, vinv);
    }
    stream_transposed4_avx2(m, out + 4 * x);
  }
  for (; x < w; ++x) {
    hsum_powers_texel<K>(ext, x, h);
    msm_out_texel<K>(rows, x, inv, out);
  }
}
#endif

// min(1, min_x finite_dist(row[x])), the ESM filter's shift, in 8 lanes combined in a fixed
// order (min is exact, so any order gives the same value).
SL_ROW_CLONES float row_min_dist(const float* row, int w) {
  float lanes[8] = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f};
  int x = 0;
  for (; x + 8 <= w; x += 8)
    for (int l = 0; l < 8; ++l) {
      const float d = finite_dist_bits(row[x + l]);
      const uint32_t take = uint32_t(0) - uint32_t(d < lanes[l]);
      lanes[l] = std::bit_cast<float>((std::bit_cast<uint32_t>(d) & take) |
                                      (std::bit_cast<uint32_t>(lanes[l]) & ~take));
    }
  float m = 1.0f;
  for (int l = 0; l < 8; ++l) m = std::min(m, lanes[l]);
  for (; x < w; ++x) m = std::min(m, finite_dist(row[x]));
  return m;
}

// The finite values of a row's n texels: out[x] = finite_dist(row[x]) (VSM's kernels' input).
SL_ROW_CLONES void finite_row(const float* row, int n, float* out) {
  for (int x = 0; x < n; ++x) out[x] = finite_dist_bits(row[x]);
}

// The fused separable box over `planes` planes of sums of type T (double; MSM's float), as a ring
// of k horizontal-sum rows per span of output columns in each band of 32 output rows
// (kTexelTile: one span over the whole width without `tiles`, else the needed tiles' runs,
// tile_spans): hrow(y, span, dst, ext) writes input row y's horizontal sums over the span's
// columns (dst[c]: span.n values of plane c; ext: scratch of planes × (w + k − 1) values);
// out_row(y, span, window, out) receives, plane after plane, the k rows' pointers of output row
// y's vertical window (rows clamped to the image) in top-to-bottom order, and scratch of
// (planes + 1) × w doubles' worth of bytes. Each input row's sums are
// computed once per band and span (plus k − 1 rows shared with the next band) and stay in cache.
// `src` (w floats per row, the distances the rows are made from) is prefetched a row ahead over
// the span's input columns: the render wrote it long before (a face is larger than the caches),
// and each span row starts a new stream the hardware prefetcher has not seen, so without the
// hint the row makers wait on memory (a prefetch changes no value).
// Optional new_row_out(y, row, span, dst, window, ext): where output row y's window has a new
// bottom row (row = y + r, inside the face), makes that row's sums into dst (its ring slots, the
// window's last row of each plane) and writes output row y in one pass, returning true; false
// leaves both to hrow and out_row.
template <class T = double, class HRow, class OutRow, class NewRowOut = std::nullptr_t>
void fused_box(int w, int h, int k, int planes, const FaceTiles* tiles, const float* src,
               const HRow& hrow, const OutRow& out_row, const NewRowOut& new_row_out = nullptr) {
  constexpr bool has_new_row_out = !std::is_same_v<NewRowOut, std::nullptr_t>;
  const int r = k / 2;
  const int bands = (h + kTexelTile - 1) / kTexelTile;
  parallel_for_chunks(size_t(bands), 1, [&](size_t b0, size_t b1) {
    // One uninitialized block, 64-byte aligned, its rows (row_len values) whole lines: a
    // kernel whose steps start at x = 0 of a row (MSM's AVX-512 row, msm_hsum_out_lines) then
    // never straddles two lines with a 64-byte load or store (with rows of w = 1030 floats, 24
    // bytes past a line each, every one of them did: README "Technique benchmark", eighteenth
    // session). Every value is written before it is read.
    constexpr size_t kLine = 64 / sizeof(T);
    const size_t row_len = (size_t(w) + kLine - 1) / kLine * kLine;
    const size_t ew = (size_t(w) + size_t(k) - 1 + kLine - 1) / kLine * kLine;
    const size_t n_ring = size_t(k) * size_t(planes) * row_len;
    // out_row's scratch: (planes + 1) × w doubles' worth of bytes, whatever T.
    const size_t n_out = (size_t(planes) + 1) * row_len * (sizeof(double) / sizeof(T));
    struct LineDelete {
      void operator()(T* p) const { ::operator delete(p, std::align_val_t(64)); }
    };
    const std::unique_ptr<T[], LineDelete> ring(static_cast<T*>(
        ::operator new((n_ring + size_t(planes) * ew + n_out) * sizeof(T), std::align_val_t(64))));
    T* const ext = ring.get() + n_ring;
    T* const out = ext + size_t(planes) * ew;
    auto slot = [&](int yy, int c) {
      return ring.get() + (size_t(yy % k) * size_t(planes) + size_t(c)) * row_len;
    };
    std::vector<T*> dst(static_cast<size_t>(planes));
    std::vector<const T*> window(size_t(planes) * size_t(k));
    std::vector<TexelSpan> spans;
    for (size_t band = b0; band < b1; ++band) {
      tile_spans(tiles, int(band), w, spans);
      const int y0 = int(band) * kTexelTile, y1 = std::min(h, y0 + kTexelTile);
      for (const TexelSpan& span : spans) {
        const SpanCols cols = span_cols(span, w, r);
        int next = std::max(0, y0 - r);
        for (int y = y0; y < y1; ++y) {
          const int last = std::min(h - 1, y + r);
          // The window's new bottom row, left to new_row_out.
          const int defer = has_new_row_out && last == y + r ? last : -1;
          for (; next <= last; ++next) {
            if (next + 1 < h)
              prefetch_bytes(src + size_t(next + 1) * size_t(w) + size_t(cols.in0),
                             size_t(cols.in_n) * sizeof(float));
            if (next == defer) break;
            for (int c = 0; c < planes; ++c) dst[size_t(c)] = slot(next, c);
            hrow(next, cols, dst.data(), ext);
          }
          for (int c = 0; c < planes; ++c)
            for (int j = -r; j <= r; ++j)
              window[size_t(c) * size_t(k) + size_t(j + r)] = slot(std::clamp(y + j, 0, h - 1), c);
          if constexpr (has_new_row_out) {
            if (next == defer) {
              ++next;
              for (int c = 0; c < planes; ++c) dst[size_t(c)] = slot(defer, c);
              if (new_row_out(y, defer, cols, dst.data(), window.data(), ext)) continue;
              hrow(defer, cols, dst.data(), ext);
            }
          }
          out_row(y, cols, window.data(), out);
        }
      }
    }
    stream_fence();  // out_row's stream copies (core/stream_copy.h) before the chunk ends
  });
}

// Calls f(std::integral_constant<int, K>) for the widths with compiled kernels; false otherwise.
template <class F>
bool with_fixed_width(int k, const F& f) {
  switch (k) {
    case 1: f(std::integral_constant<int, 1>{}); return true;
    case 3: f(std::integral_constant<int, 3>{}); return true;
    case 5: f(std::integral_constant<int, 5>{}); return true;
    case 7: f(std::integral_constant<int, 7>{}); return true;
    case 9: f(std::integral_constant<int, 9>{}); return true;
    default: return false;
  }
}

}  // namespace

namespace {

// Where filtered means and variances go: texel i's at mean[stride·i] and var[stride·i]; stride
// 1 for two planes, 2 for one interleaved plane (var = mean + 1).
struct MeanVarOut {
  float* mean;
  float* var;
  int stride;
};

// Row y's mean and variance floats of the span's columns through write(mean_row, var_row):
// straight into the planes, or (stride 2 or 4) into `scratch` (2·n floats) and then interleaved
// (stride 4: into two of each texel's four slots; EVSM4 writes its two warps' pairs side by
// side). Stored with ordinary stores: streaming VSM's 8 B per texel (core/stream_copy.h) made
// its filter 0.3 ms faster and its lookup 0.35 ms slower (the lookup then reads what the caches
// would have held), so it would only move time between the phases.
template <class Write>
void write_mean_var(const MeanVarOut& o, int w, int y, const SpanCols& s, float* scratch,
                    const Write& write) {
  const size_t at = (size_t(y) * size_t(w) + size_t(s.x0)) * size_t(o.stride);
  const int n = s.n;
  if (o.stride == 1) {
    write(o.mean + at, o.var + at);
    return;
  }
  write(scratch, scratch + n);
  if (o.stride == 2) {
    interleave_row(scratch, scratch + n, n, o.mean + at);
    return;
  }
  float* const row = o.mean + at;
  for (int x = 0; x < n; ++x) {
    row[size_t(o.stride) * size_t(x)] = scratch[x];
    row[size_t(o.stride) * size_t(x) + 1] = scratch[size_t(n) + size_t(x)];
  }
}

// Row y's filtered mean and variance from its window of K rows of each plane's horizontal sums
// (vsm_out_k's operations): straight into the interleaved plane by vsm_out_interleaved_avx512
// or _avx2 where the plane interleaves two values and that ISA is in use (isa), else through
// write_mean_var.
template <int K>
void vsm_out_row(const MeanVarOut& o, int w, int y, const SpanCols& s, const double* const* win,
                 double* scratch, double inv, ExpPath isa) {
#if defined(__x86_64__)
  if (o.stride == 2 && isa != ExpPath::scalar) {
    float* const row = o.mean + 2 * (size_t(y) * size_t(w) + size_t(s.x0));
    if (isa == ExpPath::avx512)
      vsm_out_interleaved_avx512<K>(win, s.n, inv, row);
    else
      vsm_out_interleaved_avx2<K>(win, s.n, inv, row);
    return;
  }
#else
  (void)isa;
#endif
  write_mean_var(o, w, y, s, reinterpret_cast<float*>(scratch),
                 [&](float* m, float* v) { vsm_out_k<K>(win, s.n, inv, m, v); });
}

// Filtered mean and centred variance of a two-plane row maker: make_row(y, cols, ext) fills
// plane 0 at ext and plane 1 at ext + (w + k − 1) with the span's extended row (cols.n + k − 1
// values: SpanCols).
// With `fixed` and a compiled width, the fixed-width kernels; else the runtime-k loops (their
// oracle): the same additions in the same order either way.
template <class MakeRow>
void box_mean_variance(int w, int h, int k, bool fixed, const FaceTiles* tiles, const float* src,
                       const MakeRow& make_row, const MeanVarOut& o) {
  const size_t ew = size_t(w) + size_t(k) - 1;
  const double inv = 1.0 / double(k * k);
#if defined(__x86_64__)
  const ExpPath isa = exp_path(true);  // vsm_out_interleaved_avx512 / _avx2 for stride 2
#endif
  if (fixed && with_fixed_width(k, [&](auto kc) {
        constexpr int K = decltype(kc)::value;
        fused_box(
            w, h, k, 2, tiles, src,
            [&](int y, const SpanCols& s, double* const* dst, double* ext) {
              make_row(y, s, ext);
              hsum_k<K>(ext, s.n, dst[0]);
              hsum_k<K>(ext + ew, s.n, dst[1]);
            },
            [&](int y, const SpanCols& s, const double* const* win, double* scratch) {
              vsm_out_row<K>(o, w, y, s, win, scratch, inv, isa);
            });
      }))
    return;
  fused_box(
      w, h, k, 2, tiles, src,
      [&](int y, const SpanCols& s, double* const* dst, double* ext) {
        make_row(y, s, ext);
        hsum_row(ext, s.n, k, dst[0]);
        hsum_row(ext + ew, s.n, k, dst[1]);
      },
      [&](int y, const SpanCols& s, const double* const* win, double* out) {
        vsum_rows(win, s.n, k, inv, out);
        vsum_rows(win + k, s.n, k, inv, out + w);
        // out holds the two summed rows (2·w doubles); the floats go after them in the
        // planes' scratch only when interleaving, so use a row of their own.
        float* const tmp = reinterpret_cast<float*>(out + 2 * size_t(w));
        write_mean_var(o, w, y, s, tmp, [&](float* m, float* v) {
          mean_variance_row(out, out + w, s.n, m, v);
        });
      });
}

// VSM's and EVSM's k = 3 filter (techniques/centred_window3.h: one centred 9-tap float window
// per texel): per band of 32 output rows and span of needed columns (as fused_box walks them),
// a ring of the three extended input rows make_row(y, cols, in) writes (cols.in_n floats at
// `in`, clamped at the span's ends here), each made once per band and span, the next one's
// input prefetched (fused_box says why); the output rows by centred_window3_row per `isa`.
template <class MakeRow>
void centred3_box(int w, int h, const FaceTiles* tiles, const float* src, WindowIsa isa,
                  const MeanVarOut& o, const MakeRow& make_row) {
  const int bands = (h + kTexelTile - 1) / kTexelTile;
  parallel_for_chunks(size_t(bands), 1, [&](size_t b0, size_t b1) {
    const size_t row_len = size_t(w) + 2;
    const std::unique_ptr<float[]> ring(new float[3 * row_len]);
    auto slot = [&](int y) { return ring.get() + size_t(y % 3) * row_len; };
    std::vector<TexelSpan> spans;
    for (size_t band = b0; band < b1; ++band) {
      tile_spans(tiles, int(band), w, spans);
      const int y0 = int(band) * kTexelTile, y1 = std::min(h, y0 + kTexelTile);
      for (const TexelSpan& span : spans) {
        const SpanCols cols = span_cols(span, w, 1);
        int next = std::max(0, y0 - 1);  // the first input row not made yet
        for (int y = y0; y < y1; ++y) {
          const int below = std::min(h - 1, y + 1);
          for (; next <= below; ++next) {
            if (next + 1 < h)
              prefetch_bytes(src + size_t(next + 1) * size_t(w) + size_t(cols.in0),
                             size_t(cols.in_n) * sizeof(float));
            float* const row = slot(next);
            make_row(next, cols, row + cols.lead);
            extend_span(row, cols, 3);
          }
          const size_t at = (size_t(y) * size_t(w) + size_t(cols.x0)) * size_t(o.stride);
          centred_window3_row(isa, slot(std::max(0, y - 1)), slot(y), slot(below), cols.n,
                              o.mean + at, o.var + at, o.stride);
        }
      }
    }
  });
}

// The window kernels of an ExpPath choice (the oracles' scalar one included).
WindowIsa window_isa(ExpPath p) {
  return p == ExpPath::avx512 ? WindowIsa::avx512
                              : p == ExpPath::avx2 ? WindowIsa::avx2 : WindowIsa::scalar;
}

// The fixed-width box of a float row's two moments: make_row(y, span, in) writes the span's
// span.in_n input floats at `in` (finite distances for VSM, EVSM's warp), then the row is
// clamped at its ends and hsum_moments_k forms each value and its square in double inside the
// horizontal sums; the output rows by vsm_out_row (its fused kernels per `isa`). False, having
// done nothing, for a width without a fixed kernel.
template <class MakeRow>
bool float_moments_fixed(int w, int h, int k, const FaceTiles* tiles, const float* src,
                         ExpPath isa, const MeanVarOut& o, const MakeRow& make_row) {
  const double inv = 1.0 / double(k * k);
  return with_fixed_width(k, [&](auto kc) {
    constexpr int K = decltype(kc)::value;
    fused_box(
        w, h, k, 2, tiles, src,
        [&](int y, const SpanCols& s, double* const* dst, double* ext) {
          float* const ext_f = reinterpret_cast<float*>(ext);
          make_row(y, s, ext_f + s.lead);
          extend_span(ext_f, s, k);
          hsum_moments_k<K>(ext_f, s.n, dst[0], dst[1]);
        },
        [&](int y, const SpanCols& s, const double* const* win, double* scratch) {
          vsm_out_row<K>(o, w, y, s, win, scratch, inv, isa);
        });
  });
}

void moments_double(const float* dist, int w, int h, int k, bool slope_term, bool fixed_kernels,
                    const FaceTiles* tiles, const MeanVarOut& o) {
  const int r = k / 2;
  const size_t ew = size_t(w) + size_t(k) - 1;
  // k = 3 without the slope term: the centred float window, the oracle with its scalar kernel.
  if (k == 3 && !slope_term) {
    centred3_box(w, h, tiles, dist, window_isa(exp_path(fixed_kernels)), o,
                 [&](int y, const SpanCols& s, float* in) {
                   finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, in);
                 });
    return;
  }
  // Without the slope term, d² is formed inside the horizontal sums from the float row.
  if (fixed_kernels && !slope_term &&
      float_moments_fixed(w, h, k, tiles, dist, exp_path(true), o,
                          [&](int y, const SpanCols& s, float* in) {
                            finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, in);
                          }))
    return;
  auto at = [&](int x, int y) {
    return double(finite_dist(dist[size_t(std::clamp(y, 0, h - 1)) * size_t(w) +
                                   size_t(std::clamp(x, 0, w - 1))]));
  };
  box_mean_variance(
      w, h, k, fixed_kernels, tiles, dist,
      [&](int y, const SpanCols& s, double* ext) {
        if (!slope_term) {
          moment_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ext + s.lead,
                     ext + ew + size_t(s.lead));
          extend_span(ext, s, k);
          extend_span(ext + ew, s, k);
          return;
        }
        // raw_moments' values of row y's columns [x0 − r, x0 + n + r), clamped to the image.
        for (int x = s.x0 - r; x < s.x0 + s.n + r; ++x) {
          const double d = at(x, y);
          double m2 = d * d;
          const int xc = std::clamp(x, 0, w - 1);
          const double dx = min_diff(at(xc - 1, y), d, at(xc + 1, y));
          const double dy = min_diff(at(xc, y - 1), d, at(xc, y + 1));
          m2 += double(0.25 * (dx * dx + dy * dy));
          ext[size_t(x - (s.x0 - r))] = d;
          ext[ew + size_t(x - (s.x0 - r))] = m2;
        }
      },
      o);
}

// Two planes of w × h floats.
MeanVarOut planes_out(int w, int h, std::vector<float>& mean, std::vector<float>& variance) {
  const size_t n = size_t(w) * size_t(h);
  mean.resize(n);
  variance.resize(n);
  return {mean.data(), variance.data(), 1};
}

// One interleaved plane of 2 × w × h floats.
MeanVarOut interleaved_out(int w, int h, std::vector<float>& mv) {
  mv.resize(2 * size_t(w) * size_t(h));
  return {mv.data(), mv.data() + 1, 2};
}

}  // namespace

void filter_moments_double(const float* dist, int w, int h, int k, bool slope_term,
                           std::vector<float>& mean, std::vector<float>& variance,
                           const FaceTiles* tiles) {
  moments_double(dist, w, h, k, slope_term, true, tiles, planes_out(w, h, mean, variance));
}

void filter_moments_double_oracle(const float* dist, int w, int h, int k, bool slope_term,
                                  std::vector<float>& mean, std::vector<float>& variance,
                                  const FaceTiles* tiles) {
  moments_double(dist, w, h, k, slope_term, false, tiles, planes_out(w, h, mean, variance));
}

void filter_moments_double_interleaved(const float* dist, int w, int h, int k, bool slope_term,
                                       std::vector<float>& mean_variance, const FaceTiles* tiles) {
  moments_double(dist, w, h, k, slope_term, true, tiles, interleaved_out(w, h, mean_variance));
}

namespace {

void warped_moments(const float* dist, int w, int h, int k, double c, double sign,
                    bool fixed_kernels, const FaceTiles* tiles, const MeanVarOut& o) {
  const size_t ew = size_t(w) + size_t(k) - 1;
  // k = 3: the centred float window of the float warp, the oracle with the scalar warp and
  // window kernels.
  if (k == 3) {
    const ExpPath path = exp_path(fixed_kernels);
    centred3_box(w, h, tiles, dist, window_isa(path), o,
                 [&](int y, const SpanCols& s, float* in) {
                   warp_row_f(path, dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c,
                              sign, in);
                 });
    return;
  }
  // Fixed widths: the warp as floats, its moments formed in the horizontal sums (VSM's
  // fixed path); the runtime-k oracle keeps the two double rows.
  if (fixed_kernels) {
    const ExpPath path = exp_path(true);
    if (float_moments_fixed(w, h, k, tiles, dist, path, o,
                            [&](int y, const SpanCols& s, float* in) {
                              warp_row_f(path, dist + size_t(y) * size_t(w) + size_t(s.in0),
                                         s.in_n, c, sign, in);
                            }))
      return;
  }
  box_mean_variance(
      w, h, k, fixed_kernels, tiles, dist,
      [&](int y, const SpanCols& s, double* ext) {
        warped_row_scalar(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c, sign,
                          ext + s.lead, ext + ew + size_t(s.lead));
        extend_span(ext, s, k);
        extend_span(ext + ew, s, k);
      },
      o);
}

}  // namespace

void filter_warped_moments(const float* dist, int w, int h, int k, double c, double sign,
                           std::vector<float>& mean, std::vector<float>& variance,
                           const FaceTiles* tiles) {
  warped_moments(dist, w, h, k, c, sign, true, tiles, planes_out(w, h, mean, variance));
}

void filter_warped_moments_interleaved(const float* dist, int w, int h, int k, double c,
                                       double sign, int stride, int first,
                                       std::vector<float>& out, const FaceTiles* tiles) {
  SL_CHECK((stride == 2 && first == 0) || (stride == 4 && (first == 0 || first == 2)));
  const size_t n = size_t(w) * size_t(h) * size_t(stride);
  if (out.size() != n) out.resize(n);
  float* const base = out.data() + first;
  warped_moments(dist, w, h, k, c, sign, true, tiles, {base, base + 1, stride});
}

void filter_warped_moments_oracle(const float* dist, int w, int h, int k, double c,
                                  double sign, std::vector<float>& mean,
                                  std::vector<float>& variance, const FaceTiles* tiles) {
  warped_moments(dist, w, h, k, c, sign, false, tiles, planes_out(w, h, mean, variance));
}

namespace {

// Plane c's filtered row y (a span's columns) goes to row_of(c, y, span, tmp): a row of out[c],
// or (interleaved given) the c-th of four span.n-float rows in tmp, which finish(y, span, tmp)
// then interleaves into row y. The sums are in float (moment_filter.h says why): the powers as
// power_row forms them, each horizontal sum from 0 in window order, the vertical sums in row
// order, then × 1/k² (a float), the same operations on every path.
void power_moments(const float* dist, int w, int h, int k, bool fixed_kernels,
                   const FaceTiles* tiles, std::vector<float>* out,
                   std::vector<float>* interleaved) {
  const size_t n = size_t(w) * size_t(h);
  if (interleaved)
    interleaved->resize(4 * n);
  else
    for (int c = 0; c < 4; ++c) out[c].resize(n);
  const size_t ew = size_t(w) + size_t(k) - 1;
  const float inv = 1.0f / float(k * k);
  auto make_row = [&](int y, const SpanCols& s, float* ext) {
    power_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ew, ext + s.lead);
    for (int c = 0; c < 4; ++c) extend_span(ext + size_t(c) * ew, s, k);
  };
  // Plane c's row y: in the plane, or (interleaving) in tmp's c-th row of s.n floats.
  auto row_of = [&](int c, int y, const SpanCols& s, float* tmp) {
    return interleaved ? tmp + size_t(c) * size_t(s.n)
                       : out[c].data() + size_t(y) * size_t(w) + size_t(s.x0);
  };
  // The interleaved row is made in tmp after the four planes' rows, then streamed into the map
  // (core/stream_copy.h): 16 B per texel is beyond the caches (~35 MB on the default scene's
  // cube), and not reading each line before writing it made the filter 0.55 ms faster and the
  // lookup 0.2 ms slower (AMD EPYC, README "Technique benchmark").
  const StreamCopy copy = stream_copy_kernel();
#if defined(__x86_64__)
  const ExpPath isa = interleaved ? exp_path(true) : ExpPath::scalar;
#endif
  auto finish = [&](int y, const SpanCols& s, float* tmp) {
    if (!interleaved) return;
    float* const row = tmp + 4 * size_t(s.n);
    interleave4_row(tmp, s.n, row);
    copy(row, 4 * size_t(s.n), interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0)));
  };
  // Row y's finite distances over the span's input columns, extended to its window (ext).
  auto finite_ext = [&](int y, const SpanCols& s, float* ext) {
    finite_row(dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, ext + s.lead);
    extend_span(ext, s, k);
  };
  if (fixed_kernels && with_fixed_width(k, [&](auto kc) {
        constexpr int K = decltype(kc)::value;
        fused_box<float>(
            w, h, k, 4, tiles, dist,
            [&](int y, const SpanCols& s, float* const* dst, float* ext) {
              finite_ext(y, s, ext);
              hsum_powers_k<K>(ext, s.n, dst[0], dst[1], dst[2], dst[3]);
            },
            [&](int y, const SpanCols& s, const float* const* win, float* tmp) {
#if defined(__x86_64__)
              if (isa != ExpPath::scalar) {
                float* const row =
                    interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0));
                if (isa == ExpPath::avx512)
                  msm_out_interleaved_avx512<K>(win, s.n, inv, row);
                else
                  msm_out_interleaved_avx2<K>(win, s.n, inv, row);
                return;
              }
#endif
              // tmp: 8·n of its 10·w floats.
              for (int c = 0; c < 4; ++c) mean_out_k<K>(win + c * K, s.n, inv, row_of(c, y, s, tmp));
              finish(y, s, tmp);
            },
            [&](int y, int row, const SpanCols& s, float* const* dst, const float* const* win,
                float* ext) {
#if defined(__x86_64__)
              if (isa == ExpPath::scalar) return false;
              finite_ext(row, s, ext);
              float* const out_row =
                  interleaved->data() + 4 * (size_t(y) * size_t(w) + size_t(s.x0));
              // The pages output row y + 2 will be streamed into (core/prefetch.h): without the
              // hint the cube filter took ~40 % longer on the default scene.
              if (y + 2 < h) prefetch_pages(out_row + 8 * size_t(w), 16 * size_t(s.n));
              if (isa == ExpPath::avx512)
                msm_hsum_out_avx512<K>(ext, dst, win, s.n, inv, out_row);
              else
                msm_hsum_out_avx2<K>(ext, dst, win, s.n, inv, out_row);
              return true;
#else
              return false;
#endif
            });
      }))
    return;
  fused_box<float>(
      w, h, k, 4, tiles, dist,
      [&](int y, const SpanCols& s, float* const* dst, float* ext) {
        make_row(y, s, ext);
        for (int c = 0; c < 4; ++c) hsum_row(ext + size_t(c) * ew, s.n, k, dst[c]);
      },
      [&](int y, const SpanCols& s, const float* const* win, float* tmp) {
        // tmp: 4·n floats of plane rows and 4·n of the interleaved row (of its 10·w floats).
        for (int c = 0; c < 4; ++c) vsum_rows(win + c * k, s.n, k, inv, row_of(c, y, s, tmp));
        finish(y, s, tmp);
      });
}

}  // namespace

void filter_power_moments(const float* dist, int w, int h, int k, std::vector<float>* out,
                          const FaceTiles* tiles) {
  power_moments(dist, w, h, k, true, tiles, out, nullptr);
}

void filter_power_moments_interleaved(const float* dist, int w, int h, int k,
                                      std::vector<float>& moments, const FaceTiles* tiles) {
  power_moments(dist, w, h, k, true, tiles, nullptr, &moments);
}

void filter_power_moments_oracle(const float* dist, int w, int h, int k,
                                 std::vector<float>* out, const FaceTiles* tiles) {
  power_moments(dist, w, h, k, false, tiles, out, nullptr);
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

namespace {

void esm_log(const float* dist, int w, int h, int k, double c, bool fixed_kernels,
             const FaceTiles* tiles, const float* face_min, std::vector<float>& out) {
  const size_t n = size_t(w) * size_t(h);
  out.resize(n);
  // The tiles whose inputs' range allows it go through the float path (techniques/
  // esm_float_tiles.h); the rest, and every tile of a box wider than it takes, below.
  FaceTiles rest;
  if (k <= kEsmFloatMaxWidth) {
    if (esm_float_tiles(dist, w, h, k, c, fixed_kernels, tiles, out.data(), rest) == 0) return;
    tiles = &rest;
  }
  // The image's smallest finite distance (1 when none is smaller): from the caller, or a
  // fixed-order reduction over per-row minima.
  double d_min = 1.0;
  if (face_min) {
    d_min = *face_min < 1.0f ? double(*face_min) : 1.0;
  } else {
    std::vector<float> row_min(static_cast<size_t>(h));
    parallel_for_chunks(size_t(h), 16, [&](size_t b, size_t e) {
      for (size_t y = b; y < e; ++y) row_min[y] = row_min_dist(dist + y * size_t(w), w);
    });
    for (float m : row_min) d_min = std::min(d_min, double(m));
  }
  const double inv = 1.0 / double(k * k);
  const ExpPath path = exp_path(fixed_kernels);
  auto exp_row = [&](int y, const SpanCols& s, double* ext) {
    esm_exp_row(path, dist + size_t(y) * size_t(w) + size_t(s.in0), s.in_n, c, d_min,
                ext + s.lead);
    extend_span(ext, s, k);
  };
  auto out_at = [&](int y, const SpanCols& s) {
    return out.data() + size_t(y) * size_t(w) + size_t(s.x0);
  };
  const bool fixed = fixed_kernels && with_fixed_width(k, [&](auto kc) {
    constexpr int K = decltype(kc)::value;
    fused_box(
        w, h, k, 1, tiles, dist,
        [&](int y, const SpanCols& s, double* const* dst, double* ext) {
          exp_row(y, s, ext);
          hsum_k<K>(ext, s.n, dst[0]);
        },
        [&](int y, const SpanCols& s, const double* const* win, double*) {
          esm_out_k<K>(path, win, s.n, inv, c, d_min, out_at(y, s));
        });
  });
  if (fixed) return;
  fused_box(
      w, h, k, 1, tiles, dist,
      [&](int y, const SpanCols& s, double* const* dst, double* ext) {
        exp_row(y, s, ext);
        hsum_row(ext, s.n, k, dst[0]);
      },
      [&](int y, const SpanCols& s, const double* const* win, double* filtered) {
        vsum_rows(win, s.n, k, inv, filtered);
        esm_log_row(filtered, s.n, c, d_min, out_at(y, s));
      });
}

}  // namespace

void filter_esm_log(const float* dist, int w, int h, int k, double c, std::vector<float>& out,
                    const FaceTiles* tiles, const float* face_min) {
  esm_log(dist, w, h, k, c, true, tiles, face_min, out);
}

void filter_esm_log_oracle(const float* dist, int w, int h, int k, double c,
                           std::vector<float>& out, const FaceTiles* tiles) {
  esm_log(dist, w, h, k, c, false, tiles, nullptr, out);
}

}  // namespace shadowlab

// File-local: a unity build compiles the next file in the same translation unit.
#undef SL_ROW_CLONES
