// The AVX2 table of techniques/filters/esm/esm_tile_rows.h (8 lanes). Compiled with -mavx2 -mfma
// (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

#include "core/exp_log_avx2.h"
#include "techniques/filters/esm/esm_tile_rows.h"

namespace shadowlab::esm_tile_rows_avx2 {

using namespace exp_log_avx2;

void stage_row(const float* src, int n, int lead, int pad_to, float* dst) {
  const __m256 one = _mm256_set1_ps(1.0f);
  int x = 0;
  // minps returns its second operand unless the first is smaller: NaN and +inf give 1.
  for (; x + 8 <= n; x += 8)
    _mm256_storeu_ps(dst + lead + x, _mm256_min_ps(_mm256_loadu_ps(src + x), one));
  for (; x < n; ++x) dst[lead + x] = src[x] < 1.0f ? src[x] : 1.0f;
  for (int i = 0; i < lead; ++i) dst[i] = dst[lead];
  for (int i = lead + n; i < pad_to; ++i) dst[i] = dst[lead + n - 1];
}

inline __m256 exp8_at(const float* p, __m256d vc, __m256d vs) {
  const __m256 d = _mm256_loadu_ps(p);
  const __m128 lo = _mm256_cvtpd_ps(
      _mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(d)), vs)));
  const __m128 hi = _mm256_cvtpd_ps(
      _mm256_mul_pd(vc, _mm256_sub_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(d, 1)), vs)));
  return exp_f8(_mm256_set_m128(hi, lo));
}

void exp_rows(const float* src, size_t pitch, int rows, int n, double c, double s, bool in_float,
              float* dst) {
  const __m256d vc = _mm256_set1_pd(c), vs = _mm256_set1_pd(s);
  const __m256 cf = _mm256_set1_ps(float(c)), sf = _mm256_set1_ps(float(s));
  for (int yy = 0; yy < rows; ++yy) {
    const float* row = src + size_t(yy) * pitch;
    float* const out = dst + size_t(yy) * kEsmTilePitch;
    if (in_float) {  // the same bits (in_float_exponent)
      for (int x = 0; x < n; x += 8)
        _mm256_storeu_ps(out + x, exp_f8(_mm256_mul_ps(cf, _mm256_sub_ps(_mm256_loadu_ps(row + x),
                                                                         sf))));
      continue;
    }
    for (int x = 0; x < n; x += 8) _mm256_storeu_ps(out + x, exp8_at(row + x, vc, vs));
  }
}

// 8 values a load, the last load overlapping the one before it (min and max are exact, so the
// order and the overlap change nothing); rows of fewer than 8 values one by one.
void range(const float* src, size_t pitch, int rows, int n, float& lo, float& hi) {
  if (n < 8) {
    for (int yy = 0; yy < rows; ++yy)
      for (int x = 0; x < n; ++x) {
        const float v = src[size_t(yy) * pitch + size_t(x)];
        lo = v < lo ? v : lo;
        hi = hi < v ? v : hi;
      }
    return;
  }
  __m256 vlo = _mm256_set1_ps(lo), vhi = _mm256_set1_ps(hi);
  for (int yy = 0; yy < rows; ++yy) {
    const float* row = src + size_t(yy) * pitch;
    for (int x = 0; x < n; x += 8) {
      const __m256 d = _mm256_loadu_ps(row + (x < n - 8 ? x : n - 8));
      vlo = _mm256_min_ps(vlo, d);
      vhi = _mm256_max_ps(vhi, d);
    }
  }
  alignas(32) float l[8], u[8];
  _mm256_store_ps(l, vlo);
  _mm256_store_ps(u, vhi);
  for (int i = 0; i < 8; ++i) {
    lo = l[i] < lo ? l[i] : lo;
    hi = hi < u[i] ? u[i] : hi;
  }
}

inline __m256 stored_value8(__m256 a, __m256 t_hi, __m256 t_lo) {
  __m256i e;
  const __m256 m = log_split_f8(a, e);
  const __m256 ef = _mm256_cvtepi32_ps(e);
  const __m256 big = _mm256_add_ps(t_hi, _mm256_mul_ps(ef, _mm256_set1_ps(kEsmLn2Hi12)));
  const __m256 small =
      _mm256_add_ps(_mm256_add_ps(t_lo, _mm256_mul_ps(ef, _mm256_set1_ps(kEsmLn2Lo12))), ln_m8(m));
  return _mm256_add_ps(big, small);
}

// A whole tile's sums (32 columns) in 4 registers per row, and each output row's mean straight
// into the logarithm: the scalar loops' additions in their order.
void box_tile(const float* ebuf, int th, int k, float t_hi, float t_lo, float* hbuf, float* out,
              int w) {
  for (int yy = 0; yy < th + k - 1; ++yy) {
    const float* e = ebuf + size_t(yy) * kEsmTilePitch;
    __m256 a[4];
    for (int q = 0; q < 4; ++q) a[q] = _mm256_setzero_ps();
    for (int i = 0; i < k; ++i)
      for (int q = 0; q < 4; ++q) a[q] = _mm256_add_ps(a[q], _mm256_loadu_ps(e + 8 * q + i));
    for (int q = 0; q < 4; ++q) _mm256_storeu_ps(hbuf + size_t(yy) * kEsmTileWidth + 8 * q, a[q]);
  }
  const __m256 inv = _mm256_set1_ps(1.0f / float(k * k));
  const __m256 vt_hi = _mm256_set1_ps(t_hi), vt_lo = _mm256_set1_ps(t_lo);
  for (int y = 0; y < th; ++y) {
    const float* hrow = hbuf + size_t(y) * kEsmTileWidth;
    float* const o = out + size_t(y) * size_t(w);
    for (int q = 0; q < 4; ++q) {
      __m256 a = _mm256_loadu_ps(hrow + 8 * q);
      for (int j = 1; j < k; ++j)
        a = _mm256_add_ps(a, _mm256_loadu_ps(hrow + size_t(j) * kEsmTileWidth + 8 * q));
      _mm256_storeu_ps(o + 8 * q, stored_value8(_mm256_mul_ps(a, inv), vt_hi, vt_lo));
    }
  }
}

}  // namespace shadowlab::esm_tile_rows_avx2

namespace shadowlab {
extern constinit const EsmTileKernels kEsmTilesAvx2{
    Isa::avx2, esm_tile_rows_avx2::stage_row, esm_tile_rows_avx2::exp_rows,
    esm_tile_rows_avx2::range, esm_tile_rows_avx2::box_tile};
}  // namespace shadowlab
#endif
