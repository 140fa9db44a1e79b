// The AVX-512 table of techniques/filters/moments_common/moment_rows.h: moment_rows.inl's loops vectorized for AVX-512,
// and the hand-written AVX-512 rows below (16 floats or 8 doubles a vector; MSM's fused row is
// its own algorithm here, writing whole 64-byte lines). Compiled with -mavx512f -mavx512vl
// -mavx512dq -mavx512bw (docs/simd.md). The zero-masked forms with every lane on stand for the
// unmasked ones where GCC 12's trip -Wmaybe-uninitialized (as in core/exp_log.h).
#if defined(__x86_64__)
#include <immintrin.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "core/exp_log_avx512.h"
#include "techniques/filters/msm/moment_bound.h"
#include "techniques/filters/moments_common/moment_rows.h"

namespace shadowlab::moment_rows_avx512 {

using namespace exp_log_avx512;

#include "techniques/filters/moments_common/moment_rows.inl"

// EVSM's float warp, 16 floats at a time by exp_f16; the tail by the loop.
void warp_row_f(const float* row, int w, double c, double sign, float* v) {
  const __m512 one = _mm512_set1_ps(1.0f), sc = _mm512_set1_ps(float(sign * c));
  const __m512 fs = _mm512_set1_ps(float(sign));
  int x = 0;
  for (; x + 16 <= w; x += 16) {
    const __m512 d = _mm512_maskz_min_ps(0xFFFF, _mm512_loadu_ps(row + x), one);
    const __m512 e = exp_f16(_mm512_mul_ps(sc, _mm512_sub_ps(_mm512_add_ps(d, d), one)));
    _mm512_storeu_ps(v + x, _mm512_mul_ps(fs, e));
  }
  warp_row_f_loop(row + x, w - x, c, sign, v + x);
}

// ESM's exponentials, 16 at a time: the exponents formed in double 8 at a time and rounded to
// float as esm_exponent does, then exp_wide16.
inline __m256 esm_exponent8(__m256 d, __m512d vc, __m512d vmin) {
  const __m512d dd = _mm512_maskz_cvtps_pd(0xFF, d);
  return _mm512_maskz_cvtpd_ps(0xFF, _mm512_mul_pd(vc, _mm512_sub_pd(dd, vmin)));
}

void esm_exp_row(const float* row, int w, double c, double d_min, double* out) {
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
  esm_exp_row_loop(row + x, w - x, c, d_min, out + x);
}

// ESM's output row: esm_out_k_loop's sums, then log_wide16, 16 texels at a time.
template <int K>
inline __m512d esm_window8(const double* const* r, int x, __m512d vinv) {
  __m512d a = _mm512_loadu_pd(r[0] + x);
  for (int j = 1; j < K; ++j) a = _mm512_add_pd(a, _mm512_loadu_pd(r[j] + x));
  return _mm512_mul_pd(a, vinv);
}

template <int K>
void esm_out_k(const double* const* rows, int w, double inv, double c, double d_min,
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
  esm_out_k_loop<K>(r, w - x, inv, c, d_min, out + x);
}

template <int K>
inline __m512d sum_rows8(const double* const* rows, int x) {
  __m512d a = _mm512_loadu_pd(rows[0] + x);
  for (int j = 1; j < K; ++j) a = _mm512_add_pd(a, _mm512_loadu_pd(rows[j] + x));
  return a;
}

// VSM's (and EVSM's two-value) output row straight into the interleaved plane: vsm_out_k's
// sums, products and positive part for both planes, 8 texels at a time, zipped to (mean,
// variance) per texel and stored as one 64-byte line per 8 texels with ordinary stores (VSM
// keeps its map in the caches for the lookup: docs/performance.md). Texels before the first
// line and after the last whole 8 go one by one in the same operations.
template <int K>
void vsm_out_interleaved(const double* const* rows, int w, double inv, float* out) {
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

// Four planes' 16 texels (m[c]: plane c, texels x .. x + 15) transposed to (m1 m2 m3 m4) per
// texel: line[q] holds texels 4q .. 4q + 3, the q-th 64 bytes of the interleaved row.
inline void transpose4(const __m512* m, __m512* line) {
  // Within each 128-bit lane (texels 4q .. 4q + 3): t0, t1 planes 0 1 interleaved, t2, t3
  // planes 2 3; u_i texel 4q + i's four moments in lane q.
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

// MSM's four planes' output row straight into the interleaved map: mean_out_k's float sums and
// products for planes c = 0..3, 16 texels at a time, transposed and written as four 64-byte
// lines with non-temporal stores (as core/stream_copy.h writes them; the caller fences). What
// mean_out_k, interleave4_row and the stream copy do in three passes, in one. Non-temporal
// stores need aligned addresses: a row that cannot reach a line on a texel boundary (never for
// the map's 16-byte aligned storage) goes one texel at a time.
template <int K>
void msm_out_interleaved(const float* const* rows, int w, float inv, float* out) {
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
    __m512 line[4];
    transpose4(m, line);
    for (int q = 0; q < 4; ++q) _mm512_stream_ps(out + 4 * x + 16 * q, line[q]);
  }
  for (; x < w; ++x) msm_out_texel<K>(rows, x, inv, out);
}

// 16 floats at p, or (Partial) the lanes in `lanes` with the others zero and unread.
template <bool Partial>
inline __m512 load16(__mmask16 lanes, const float* p) {
  if constexpr (Partial) return _mm512_maskz_loadu_ps(lanes, p);
  else return _mm512_loadu_ps(p);
}

// The four window means of texels x .. x + 15 for msm_hsum_out (m[c]: plane c), the window's
// new bottom row's sums stored into h[c] + x on the way; or (Partial) the lanes in `lanes`
// only, by masked loads (which read nothing past a row's end) and masked stores. The lanes left
// out compute on zeros and are never stored, so each texel gets the same operations whichever
// step it falls in.
template <int K, bool Partial>
inline void msm_hsum_means16(const float* ext, float* const* h, const float* const* r, int x,
                             __mmask16 lanes, __m512 vinv, __m512* m) {
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
inline void store_line4(float* line, int t0, int n, __m512 v) {
  const int lo = t0 > 0 ? t0 : 0, hi = t0 + 4 < n ? t0 + 4 : n;
  if (lo == t0 && hi == t0 + 4) {
    _mm512_stream_ps(line, v);
  } else if (lo < hi) {
    const unsigned bits = ((1u << (4 * (hi - t0))) - 1u) & ~((1u << (4 * (lo - t0))) - 1u);
    _mm512_mask_storeu_ps(line, __mmask16(bits), v);
  }
}

// msm_hsum_out for an output row whose texel 0 lies S texels (16·S bytes) past a 64-byte line.
// The steps run at x = 0, 16, 32, …, so the ring's rows (64-byte aligned, fused_box) are read
// and written on whole lines; output line j (texels 4j − S .. 4j − S + 3) is the last S texels
// of one transposed line and the first 4 − S of the next, one valignd, and goes out whole
// (non-temporal) except at the row's two ends (store_line4).
template <int K, int S>
void msm_hsum_out_lines(const float* ext, float* const* h, const float* const* r, int w,
                        __m512 vinv, float* out) {
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
    transpose4(m, line);
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

// hsum_powers_k for the window's new bottom row (its sums into h[0..3]) and msm_out_interleaved
// for the output row above it, in one pass of 16 texels at a time: rows[c·K + K − 1] is h[c],
// the K − 1 rows above it are read as before, and the new sums are added last from registers
// (the row order of mean_out_k). Why one pass: the output's non-temporal stores (16 B a texel)
// had a pass of their own while the row sums' pass wrote nothing; here the arithmetic can run
// while they drain (docs/performance.md).
template <int K>
void msm_hsum_out(const float* ext, float* const* h, const float* const* rows, int w, float inv,
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

constexpr MomentRowKernels table() {
  MomentRowKernels t = plain_table(Isa::avx512);
  t.warp_row_f = warp_row_f;
  t.esm_exp_row = esm_exp_row;
  set_widths(t.esm_out_k, SL_MOMENT_WIDTHS(esm_out_k));
  set_widths(t.vsm_out_interleaved, SL_MOMENT_WIDTHS(vsm_out_interleaved));
  set_widths(t.msm_out_interleaved, SL_MOMENT_WIDTHS(msm_out_interleaved));
  set_widths(t.msm_hsum_out, SL_MOMENT_WIDTHS(msm_hsum_out));
  return t;
}

}  // namespace shadowlab::moment_rows_avx512

namespace shadowlab {
extern constinit const MomentRowKernels kMomentRowsAvx512 = moment_rows_avx512::table();
}  // namespace shadowlab
#endif
