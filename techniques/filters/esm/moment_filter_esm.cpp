// ESM's filter (techniques/filters/moments_common/moment_filter.h): the box filter of e^(c·(d − d_min)) in double and
// its logarithm, c·d_min + ln(mean), stored as float.
#include "techniques/filters/moments_common/moment_filter.h"

#include "techniques/filters/moments_common/moment_box.h"

namespace shadowlab {
namespace {

// ESM's exponential of one row: out[x] = e^(c·(d − d_min)), d = finite_dist, by exp_wide of
// the exponent rounded once to float: c·(d − d_min) in double (d − d_min is exact there), then
// float. Why float precision is enough here: docs/techniques/esm.md, precision.
inline float esm_exponent(float d, double c, double d_min) {
  return float(c * (double(d) - d_min));
}
SL_ROW_CLONES void esm_exp_row_scalar(const float* row, int w, double c, double d_min,
                                      double* out) {
  for (int x = 0; x < w; ++x) out[x] = exp_wide(esm_exponent(finite_dist_bits(row[x]), c, d_min));
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
#endif

void esm_exp_row(Isa path, const float* row, int w, double c, double d_min, double* out) {
#if defined(__x86_64__)
  if (path == Isa::avx512) return esm_exp_row_avx512(row, w, c, d_min, out);
  if (path == Isa::avx2) return esm_exp_row_avx2(row, w, c, d_min, out);
#endif
  esm_exp_row_scalar(row, w, c, d_min, out);
}

// ESM's occluder term of one filtered row: c·d_min + ln(filtered).
SL_ROW_CLONES void esm_log_row(const double* filtered, int w, double c, double d_min,
                              float* out) {
  for (int x = 0; x < w; ++x) out[x] = float(c * d_min + log_wide(filtered[x]));
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
void esm_out_k(Isa path, const double* const* rows, int w, double inv, double c,
               double d_min, float* out) {
#if defined(__x86_64__)
  if (path == Isa::avx512) return esm_out_k_avx512<K>(rows, w, inv, c, d_min, out);
  if (path == Isa::avx2) return esm_out_k_avx2<K>(rows, w, inv, c, d_min, out);
#endif
  esm_out_k_scalar<K>(rows, w, inv, c, d_min, out);
}

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

}  // namespace

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
  const Isa path = exp_path(fixed_kernels);
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
