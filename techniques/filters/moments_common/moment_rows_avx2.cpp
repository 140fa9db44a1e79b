// The AVX2 table of techniques/filters/moments_common/moment_rows.h: moment_rows.inl's loops vectorized for AVX2, and
// the hand-written AVX2 rows below (8 floats or 4 doubles a vector). Compiled with -mavx2 -mfma
// (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/exp_log_avx2.h"
#include "techniques/filters/msm/moment_bound.h"
#include "techniques/filters/moments_common/moment_rows.h"

namespace shadowlab::moment_rows_avx2 {

using namespace exp_log_avx2;

#include "techniques/filters/moments_common/moment_rows.inl"

// EVSM's float warp, 8 floats at a time by exp_f8; min(d, 1) is finite_dist (minps returns its
// second operand unless d < 1, NaN included); the tail by the loop.
void warp_row_f(const float* row, int w, double c, double sign, float* v) {
  const __m256 one = _mm256_set1_ps(1.0f), sc = _mm256_set1_ps(float(sign * c));
  const __m256 fs = _mm256_set1_ps(float(sign));
  int x = 0;
  for (; x + 8 <= w; x += 8) {
    const __m256 d = _mm256_min_ps(_mm256_loadu_ps(row + x), one);
    const __m256 e = exp_f8(_mm256_mul_ps(sc, _mm256_sub_ps(_mm256_add_ps(d, d), one)));
    _mm256_storeu_ps(v + x, _mm256_mul_ps(fs, e));
  }
  warp_row_f_loop(row + x, w - x, c, sign, v + x);
}

// ESM's exponentials, 8 at a time: the exponents formed in double 4 at a time and rounded to
// float as esm_exponent does, then exp_wide8.
inline __m128 esm_exponent4(__m128 d, __m256d vc, __m256d vmin) {
  return _mm256_cvtpd_ps(_mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(d), vmin)));
}

void esm_exp_row(const float* row, int w, double c, double d_min, double* out) {
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
  esm_exp_row_loop(row + x, w - x, c, d_min, out + x);
}

// ESM's output row: esm_out_k_loop's sums, then log_wide8, 8 texels at a time.
template <int K>
inline __m256d esm_window4(const double* const* r, int x, __m256d vinv) {
  __m256d a = _mm256_loadu_pd(r[0] + x);
  for (int j = 1; j < K; ++j) a = _mm256_add_pd(a, _mm256_loadu_pd(r[j] + x));
  return _mm256_mul_pd(a, vinv);
}

template <int K>
void esm_out_k(const double* const* rows, int w, double inv, double c, double d_min,
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
  esm_out_k_loop<K>(r, w - x, inv, c, d_min, out + x);
}

// VSM's (and EVSM's two-value) output row straight into the interleaved plane: vsm_out_k's
// sums, products and positive part for both planes, 4 texels (one 32-byte store) a step; what
// vsm_out_k into scratch and interleave_row do in two passes, in one. Texels before the first
// line and after the last whole 4 go one by one in the same operations.
template <int K>
void vsm_out_interleaved(const double* const* rows, int w, double inv, float* out) {
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

// Four planes' 8 texels (m[c]: plane c) transposed to (m1 m2 m3 m4) per texel and written as two
// 64-byte lines at out (64-byte aligned) with non-temporal stores.
inline void stream_transposed4(const __m256* m, float* out) {
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

// MSM's four planes' output row straight into the interleaved map: mean_out_k's float sums and
// products, 8 texels (one 4 × 8 transpose, two 64-byte lines of streamed stores) a step; what
// mean_out_k, interleave4_row and the stream copy do in three passes, in one. Non-temporal
// stores need aligned addresses: a row that cannot reach a line on a texel boundary goes one
// texel at a time.
template <int K>
void msm_out_interleaved(const float* const* rows, int w, float inv, float* out) {
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
    stream_transposed4(m, out + 4 * x);
  }
  for (; x < w; ++x) msm_out_texel<K>(rows, x, inv, out);
}

// hsum_powers_k for the window's new bottom row (its sums into h[0..3]) and msm_out_interleaved
// for the output row above it, in one pass, 8 texels a step: rows[c·K + K − 1] is h[c], the
// K − 1 rows above it are read as before, and the new sums are added last from registers (the
// row order of mean_out_k).
template <int K>
void msm_hsum_out(const float* ext, float* const* h, const float* const* rows, int w, float inv,
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
    stream_transposed4(m, out + 4 * x);
  }
  for (; x < w; ++x) {
    hsum_powers_texel<K>(ext, x, h);
    msm_out_texel<K>(rows, x, inv, out);
  }
}

constexpr MomentRowKernels table() {
  MomentRowKernels t = plain_table(Isa::avx2);
  t.warp_row_f = warp_row_f;
  t.esm_exp_row = esm_exp_row;
  set_widths(t.esm_out_k, SL_MOMENT_WIDTHS(esm_out_k));
  set_widths(t.vsm_out_interleaved, SL_MOMENT_WIDTHS(vsm_out_interleaved));
  set_widths(t.msm_out_interleaved, SL_MOMENT_WIDTHS(msm_out_interleaved));
  set_widths(t.msm_hsum_out, SL_MOMENT_WIDTHS(msm_hsum_out));
  return t;
}

}  // namespace shadowlab::moment_rows_avx2

namespace shadowlab {
extern constinit const MomentRowKernels kMomentRowsAvx2 = moment_rows_avx2::table();
}  // namespace shadowlab
#endif
