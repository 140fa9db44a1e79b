#include "techniques/centred_window3.h"

#include <algorithm>
#include <cstdint>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "core/simd_target.h"

namespace shadowlab {
namespace {

// 1/3 and 1/9 rounded to float: the kernels multiply by them (a product per lane is cheaper
// than a division, and every kernel uses the same constants, so the same bits).
constexpr float kThird = 1.0f / 3.0f;
constexpr float kNinth = 1.0f / 9.0f;

// Texel x of a row: the header's sums, in window order, then the mean and the positive part of
// the variance (a NaN gives +0, as v > 0 is false for it).
inline void window_texel(const float* r0, const float* r1, const float* r2, int x, float& mean,
                         float& var) {
  const float c = r1[x + 1];
  float s1 = 0.0f, s2 = 0.0f;
  for (const float* r : {r0, r1, r2})
    for (int i = 0; i < 3; ++i) {
      const float d = r[x + i] - c;
      s1 += d;
      const float u = d * kThird;
      s2 += u * u;
    }
  const float m = s1 * kNinth;
  mean = c + m;
  const float v = s2 - m * m;
  var = v > 0.0f ? v : 0.0f;
}

void row_scalar(const float* r0, const float* r1, const float* r2, int from, int n, float* mean,
                float* var, int stride) {
  for (int x = from; x < n; ++x)
    window_texel(r0, r1, r2, x, mean[size_t(stride) * size_t(x)], var[size_t(stride) * size_t(x)]);
}

// Texels to compute one by one before the interleaved output (8 bytes per texel) starts a
// 64-byte line, so the vector stores after them do not straddle lines (a store across two
// lines costs about two); n when no texel boundary falls on a line (then every texel goes one
// by one, which only a misaligned caller's storage would cause).
inline int texels_to_line(const float* out, int n) {
  const uintptr_t bytes = (64 - (reinterpret_cast<uintptr_t>(out) & 63)) & 63;
  if (bytes % 8 != 0) return n;
  return std::min(n, int(bytes / 8));
}

#if defined(__x86_64__)
// 16 texels' mean and variance from x on: window_texel's operations lane by lane.
SL_TARGET("avx512f") inline void window16(const float* r0, const float* r1, const float* r2,
                                          int x, __m512& mean, __m512& var) {
  const __m512 c = _mm512_loadu_ps(r1 + x + 1), third = _mm512_set1_ps(kThird);
  const __m512 zero = _mm512_setzero_ps();
  __m512 s1 = zero, s2 = zero;
  for (const float* r : {r0, r1, r2})
    for (int i = 0; i < 3; ++i) {
      const __m512 d = _mm512_sub_ps(_mm512_loadu_ps(r + x + i), c);
      s1 = _mm512_add_ps(s1, d);
      const __m512 u = _mm512_mul_ps(d, third);
      s2 = _mm512_add_ps(s2, _mm512_mul_ps(u, u));
    }
  const __m512 m = _mm512_mul_ps(s1, _mm512_set1_ps(kNinth));
  mean = _mm512_add_ps(c, m);
  const __m512 v = _mm512_sub_ps(s2, _mm512_mul_ps(m, m));
  var = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(v, zero, _CMP_GT_OQ), v);
}

SL_TARGET("avx512f") void row_avx512(const float* r0, const float* r1, const float* r2, int n,
                                     float* mean, float* var, int stride) {
  const bool zip = stride == 2 && var == mean + 1;
  int x = zip ? texels_to_line(mean, n) : 0;
  row_scalar(r0, r1, r2, 0, x, mean, var, stride);
  // Per 128-bit lane q, t0 holds texels 4q, 4q + 1 (mean, variance each) and t1 texels 4q + 2,
  // 4q + 3; the two index vectors take lanes 0 1 and 2 3 of both in texel order.
  const __m512i first = _mm512_setr_epi32(0, 1, 2, 3, 16, 17, 18, 19, 4, 5, 6, 7, 20, 21, 22, 23);
  const __m512i second =
      _mm512_setr_epi32(8, 9, 10, 11, 24, 25, 26, 27, 12, 13, 14, 15, 28, 29, 30, 31);
  for (; x + 16 <= n; x += 16) {
    __m512 m, v;
    window16(r0, r1, r2, x, m, v);
    if (zip) {
      // The zero-masked unpacks with every lane on: GCC 12's unmasked ones trip
      // -Wmaybe-uninitialized (as in core/exp_log.h).
      const __m512 t0 = _mm512_maskz_unpacklo_ps(0xFFFF, m, v);
      const __m512 t1 = _mm512_maskz_unpackhi_ps(0xFFFF, m, v);
      _mm512_storeu_ps(mean + 2 * x, _mm512_permutex2var_ps(t0, first, t1));
      _mm512_storeu_ps(mean + 2 * x + 16, _mm512_permutex2var_ps(t0, second, t1));
      continue;
    }
    alignas(64) float mb[16], vb[16];
    _mm512_store_ps(mb, m);
    _mm512_store_ps(vb, v);
    for (int l = 0; l < 16; ++l) {
      mean[size_t(stride) * size_t(x + l)] = mb[l];
      var[size_t(stride) * size_t(x + l)] = vb[l];
    }
  }
  row_scalar(r0, r1, r2, x, n, mean, var, stride);
}

// The same 8 texels at a time (AVX2).
SL_TARGET("avx2") inline void window8(const float* r0, const float* r1, const float* r2, int x,
                                      __m256& mean, __m256& var) {
  const __m256 c = _mm256_loadu_ps(r1 + x + 1), third = _mm256_set1_ps(kThird);
  const __m256 zero = _mm256_setzero_ps();
  __m256 s1 = zero, s2 = zero;
  for (const float* r : {r0, r1, r2})
    for (int i = 0; i < 3; ++i) {
      const __m256 d = _mm256_sub_ps(_mm256_loadu_ps(r + x + i), c);
      s1 = _mm256_add_ps(s1, d);
      const __m256 u = _mm256_mul_ps(d, third);
      s2 = _mm256_add_ps(s2, _mm256_mul_ps(u, u));
    }
  const __m256 m = _mm256_mul_ps(s1, _mm256_set1_ps(kNinth));
  mean = _mm256_add_ps(c, m);
  const __m256 v = _mm256_sub_ps(s2, _mm256_mul_ps(m, m));
  var = _mm256_and_ps(v, _mm256_cmp_ps(v, zero, _CMP_GT_OQ));
}

SL_TARGET("avx2") void row_avx2(const float* r0, const float* r1, const float* r2, int n,
                                float* mean, float* var, int stride) {
  const bool zip = stride == 2 && var == mean + 1;
  int x = zip ? texels_to_line(mean, n) : 0;
  row_scalar(r0, r1, r2, 0, x, mean, var, stride);
  for (; x + 8 <= n; x += 8) {
    __m256 m, v;
    window8(r0, r1, r2, x, m, v);
    if (zip) {
      const __m256 lo = _mm256_unpacklo_ps(m, v);  // texels 0 1 | 4 5
      const __m256 hi = _mm256_unpackhi_ps(m, v);  // texels 2 3 | 6 7
      _mm256_storeu_ps(mean + 2 * x, _mm256_permute2f128_ps(lo, hi, 0x20));
      _mm256_storeu_ps(mean + 2 * x + 8, _mm256_permute2f128_ps(lo, hi, 0x31));
      continue;
    }
    alignas(32) float mb[8], vb[8];
    _mm256_store_ps(mb, m);
    _mm256_store_ps(vb, v);
    for (int l = 0; l < 8; ++l) {
      mean[size_t(stride) * size_t(x + l)] = mb[l];
      var[size_t(stride) * size_t(x + l)] = vb[l];
    }
  }
  row_scalar(r0, r1, r2, x, n, mean, var, stride);
}
#endif

}  // namespace

void centred_window3_row(WindowIsa isa, const float* r0, const float* r1, const float* r2, int n,
                         float* mean, float* var, int stride) {
#if defined(__x86_64__)
  if (isa == WindowIsa::avx512) return row_avx512(r0, r1, r2, n, mean, var, stride);
  if (isa == WindowIsa::avx2) return row_avx2(r0, r1, r2, n, mean, var, stride);
#endif
  row_scalar(r0, r1, r2, 0, n, mean, var, stride);
}

}  // namespace shadowlab
