// The AVX-512 table of techniques/filters/esm/esm_tile_rows.h: 16-lane exponentials and tile box; staging
// and the range are the AVX2 table's (bound by memory). Compiled with -mavx512f -mavx512vl
// -mavx512dq -mavx512bw (docs/simd.md). The zero-masked conversions with every lane on stand for
// the unmasked ones where GCC 12's trip -Wmaybe-uninitialized (as in core/exp_log.h).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

#include "core/exp_log_avx512.h"
#include "techniques/filters/esm/esm_tile_rows.h"

namespace shadowlab {
namespace esm_tile_rows_avx2 {
void stage_row(const float* src, int n, int lead, int pad_to, float* dst);
void range(const float* src, size_t pitch, int rows, int n, float& lo, float& hi);
}  // namespace esm_tile_rows_avx2
}  // namespace shadowlab

namespace shadowlab::esm_tile_rows_avx512 {

using namespace exp_log_avx512;

inline __m256 exp8_at(const float* p, __m256d vc, __m256d vs) {
  const __m256 d = _mm256_loadu_ps(p);
  const __m128 lo = _mm256_cvtpd_ps(
      _mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(d)), vs)));
  const __m128 hi = _mm256_cvtpd_ps(
      _mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(d, 1)), vs)));
  return exp_f8(_mm256_set_m128(hi, lo));
}

// 16 lanes while 9 or more values remain, else 8 (exp_f8 gives exp_f16's bits).
void exp_rows(const float* src, size_t pitch, int rows, int n, double c, double s, bool in_float,
              float* dst) {
  const __m512d vc = _mm512_set1_pd(c), vs = _mm512_set1_pd(s);
  const __m256d vc4 = _mm256_set1_pd(c), vs4 = _mm256_set1_pd(s);
  const __m512 cf = _mm512_set1_ps(float(c)), sf = _mm512_set1_ps(float(s));
  const __m256 cf8 = _mm256_set1_ps(float(c)), sf8 = _mm256_set1_ps(float(s));
  for (int yy = 0; yy < rows; ++yy) {
    const float* row = src + size_t(yy) * pitch;
    float* const out = dst + size_t(yy) * kEsmTilePitch;
    int x = 0;
    if (in_float) {  // the same bits (in_float_exponent)
      for (; n - x > 8; x += 16)
        _mm512_storeu_ps(out + x, exp_f16(_mm512_mul_ps(cf, _mm512_sub_ps(_mm512_loadu_ps(row + x),
                                                                          sf))));
      if (x < n)
        _mm256_storeu_ps(out + x, exp_f8(_mm256_mul_ps(cf8, _mm256_sub_ps(_mm256_loadu_ps(row + x),
                                                                          sf8))));
      continue;
    }
    for (; n - x > 8; x += 16) {
      const __m512 d = _mm512_loadu_ps(row + x);
      const __m256 lo = _mm512_maskz_cvtpd_ps(
          0xFF, _mm512_mul_pd(vc, _mm512_sub_pd(_mm512_maskz_cvtps_pd(0xFF, half_ps(d, 0)), vs)));
      const __m256 hi = _mm512_maskz_cvtpd_ps(
          0xFF, _mm512_mul_pd(vc, _mm512_sub_pd(_mm512_maskz_cvtps_pd(0xFF, half_ps(d, 1)), vs)));
      _mm512_storeu_ps(out + x, exp_f16(join_ps(lo, hi)));
    }
    if (x < n) _mm256_storeu_ps(out + x, exp8_at(row + x, vc4, vs4));
  }
}

inline __m512 stored_value16(__m512 a, __m512 t_hi, __m512 t_lo) {
  __m512i e;
  const __m512 m = log_split_f16(a, e);
  const __m512 ef = _mm512_maskz_cvtepi32_ps(0xFFFF, e);
  const __m512 big = _mm512_add_ps(t_hi, _mm512_mul_ps(ef, _mm512_set1_ps(kEsmLn2Hi12)));
  const __m512 small =
      _mm512_add_ps(_mm512_add_ps(t_lo, _mm512_mul_ps(ef, _mm512_set1_ps(kEsmLn2Lo12))), ln_m16(m));
  return _mm512_add_ps(big, small);
}

// A whole tile's sums (32 columns) in 2 registers per row, and each output row's mean straight
// into the logarithm: the scalar loops' additions in their order.
void box_tile(const float* ebuf, int th, int k, float t_hi, float t_lo, float* hbuf, float* out,
              int w) {
  for (int yy = 0; yy < th + k - 1; ++yy) {
    const float* e = ebuf + size_t(yy) * kEsmTilePitch;
    __m512 a0 = _mm512_setzero_ps(), a1 = _mm512_setzero_ps();
    for (int i = 0; i < k; ++i) {
      a0 = _mm512_add_ps(a0, _mm512_loadu_ps(e + i));
      a1 = _mm512_add_ps(a1, _mm512_loadu_ps(e + 16 + i));
    }
    _mm512_storeu_ps(hbuf + size_t(yy) * kEsmTileWidth, a0);
    _mm512_storeu_ps(hbuf + size_t(yy) * kEsmTileWidth + 16, a1);
  }
  const __m512 inv = _mm512_set1_ps(1.0f / float(k * k));
  const __m512 vt_hi = _mm512_set1_ps(t_hi), vt_lo = _mm512_set1_ps(t_lo);
  for (int y = 0; y < th; ++y) {
    const float* hrow = hbuf + size_t(y) * kEsmTileWidth;
    float* const o = out + size_t(y) * size_t(w);
    for (int q = 0; q < 2; ++q) {
      __m512 a = _mm512_loadu_ps(hrow + 16 * q);
      for (int j = 1; j < k; ++j)
        a = _mm512_add_ps(a, _mm512_loadu_ps(hrow + size_t(j) * kEsmTileWidth + 16 * q));
      _mm512_storeu_ps(o + 16 * q, stored_value16(_mm512_mul_ps(a, inv), vt_hi, vt_lo));
    }
  }
}

}  // namespace shadowlab::esm_tile_rows_avx512

namespace shadowlab {
extern constinit const EsmTileKernels kEsmTilesAvx512{
    Isa::avx512, esm_tile_rows_avx2::stage_row, esm_tile_rows_avx512::exp_rows,
    esm_tile_rows_avx2::range, esm_tile_rows_avx512::box_tile};
}  // namespace shadowlab
#endif
