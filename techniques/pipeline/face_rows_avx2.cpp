// The AVX2 rows of techniques/pipeline/face_rows.h: face_rows.inl's loops vectorized for AVX2, and the
// rows with their minimum in hand-written AVX2. Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cmath>
#include <limits>

#include "techniques/pipeline/face_rows.h"

namespace shadowlab::face_rows_avx2 {

#include "techniques/pipeline/face_rows.inl"

// radial_row over the rows [y0, y1) of a tile (v of row y: top − (y + ½)·dv) and the minimum of
// the results, in one AVX2 loop: radial_row's operations in its order per lane (u = u0 +
// (x + ½)·du; sqrt((1 + u²) + v²) · inv_far / row[x], no FMA), so each texel gets its bits. One
// call per tile: per row, the call's own cost was a third of the loop's.
float radial_tile_min(float* out, size_t stride, int x0, int x1, int y0, int y1, float u0,
                      float du, float top, float dv, float inv_far) {
  // _mm256_min_ps(a, b) is a < b ? a : b per lane: with the new values as a, a NaN keeps b.
  __m256 m = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  float tail_min = std::numeric_limits<float>::infinity();
  const __m256 lane = _mm256_setr_ps(0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f, 7.5f);
  const __m256 one = _mm256_set1_ps(1.0f), vu0 = _mm256_set1_ps(u0), vdu = _mm256_set1_ps(du);
  const __m256 vfar = _mm256_set1_ps(inv_far);
  for (int y = y0; y < y1; ++y) {
    float* const row = out + size_t(y) * stride;
    const float v = top - (float(y) + 0.5f) * dv;
    const __m256 vv = _mm256_set1_ps(v * v);
    int x = x0;
    for (; x + 8 <= x1; x += 8) {
      // float(x) + (l + 0.5) is exact for x < 2^22 (faces are at most 16384 texels wide), as
      // float(x) + 0.5 per texel in radial_row.
      const __m256 xs = _mm256_add_ps(_mm256_set1_ps(float(x)), lane);
      const __m256 u = _mm256_add_ps(vu0, _mm256_mul_ps(xs, vdu));
      const __m256 r2 = _mm256_add_ps(_mm256_add_ps(one, _mm256_mul_ps(u, u)), vv);
      const __m256 d =
          _mm256_div_ps(_mm256_mul_ps(_mm256_sqrt_ps(r2), vfar), _mm256_loadu_ps(row + x));
      _mm256_storeu_ps(row + x, d);
      m = _mm256_min_ps(d, m);
    }
    for (; x < x1; ++x) {  // radial_row's scalar form
      const float u = u0 + (float(x) + 0.5f) * du;
      row[x] = std::sqrt(1.0f + u * u + v * v) * inv_far / row[x];
      tail_min = row[x] < tail_min ? row[x] : tail_min;
    }
  }
  alignas(32) float lanes[8];
  _mm256_store_ps(lanes, m);
  for (const float l : lanes) tail_min = l < tail_min ? l : tail_min;
  return tail_min;
}

// paraboloid_row and face_row_min_scalar in one AVX2 loop (inv_far / row[x] per lane: its bits).
float paraboloid_row_min(float* row, int x0, int x1, float inv_far) {
  __m256 m = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  int x = x0;
  for (; x + 8 <= x1; x += 8) {
    const __m256 d = _mm256_div_ps(_mm256_set1_ps(inv_far), _mm256_loadu_ps(row + x));
    _mm256_storeu_ps(row + x, d);
    m = _mm256_min_ps(d, m);
  }
  alignas(32) float lanes[8];
  _mm256_store_ps(lanes, m);
  for (int i = x; i < x1; ++i) row[i] = inv_far / row[i];
  float r = face_row_min_scalar(row, x, x1);
  for (const float l : lanes) r = l < r ? l : r;
  return r;
}

}  // namespace shadowlab::face_rows_avx2
#endif
