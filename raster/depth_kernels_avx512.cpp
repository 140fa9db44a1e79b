// The AVX-512 whole-triangle walk of raster/depth_kernels.h. Compiled with -mavx512f -mavx512vl
// -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "raster/depth_kernels.h"
#include "raster/setup.h"

namespace shadowlab::depth_kernels_avx512 {

// Minimum and maximum (no standard template in an ISA file).
[[gnu::always_inline]] inline int imin(int a, int b) { return a < b ? a : b; }
[[gnu::always_inline]] inline int imax(int a, int b) { return a < b ? b : a; }
[[gnu::always_inline]] inline int64_t min64(int64_t a, int64_t b) { return a < b ? a : b; }
[[gnu::always_inline]] inline int64_t max64(int64_t a, int64_t b) { return a < b ? b : a; }

// The plane's x term of a block's 8 lanes: z_dx * float(ox + i).
[[gnu::always_inline]] inline __m256 plane_x(float z_dx, int ox) {
  const __m256 x = _mm256_cvtepi32_ps(
      _mm256_add_epi32(_mm256_set1_epi32(ox), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  return _mm256_mul_ps(_mm256_set1_ps(z_dx), x);
}

// What a block's rows share, in registers: the stores may alias the caller's records as far as
// the compiler knows, which would otherwise reload every field on every row.
struct PlaneRows {
  float z0, z_dy;
  int oy, rows;
};

// The rows of one block, AVX-512: ev holds each edge's 8 lanes at the first row; `lanes` the
// lanes that are pixels (all but in a block cut by the viewport's right edge, whose other lanes
// are neither read nor written). Covered lanes and the depth test are mask registers, stores are
// masked; no branch on a row's coverage (as the AVX2 rows).
[[gnu::always_inline]] inline void block_rows(__m512i* ev, const __m512i* dy, bool inside,
                                              __mmask8 lanes, __m256 zx, const PlaneRows& p,
                                              __m256 z_lo, __m256 z_hi, __m256i id, float* z,
                                              uint32_t* ids, size_t stride) {
  const __m512i zero = _mm512_setzero_si512();
  for (int r = 0; r < p.rows; ++r) {
    __mmask8 covered = lanes;
    if (!inside) {
      const __m512i any = _mm512_or_si512(_mm512_or_si512(ev[0], ev[1]), ev[2]);
      covered = __mmask8(covered & _mm512_cmpge_epi64_mask(any, zero));
      for (int k = 0; k < 3; ++k) ev[k] = _mm512_add_epi64(ev[k], dy[k]);
    }
    const float zy = p.z0 + p.z_dy * float(p.oy + r);
    const __m256 iw =
        _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(_mm256_set1_ps(zy), zx), z_lo), z_hi);
    float* row = z + size_t(r) * stride;
    const __mmask8 nearer =
        _mm256_mask_cmp_ps_mask(covered, iw, _mm256_maskz_loadu_ps(covered, row), _CMP_GT_OQ);
    _mm256_mask_storeu_ps(row, nearer, iw);
    if (ids) _mm256_mask_storeu_epi32(ids + size_t(r) * stride, nearer, id);
  }
}

// A triangle's whole walk in a tile (rasterize_depth_in_rect's, in registers) with
// block_rows per block; the lane offsets step_x · i once per triangle (vpmullq: the same
// exact int64 products as lane_x).
void triangle(const TriangleSetup& s, int x0, int y0, int x1, int y1, float* z, uint32_t* ids,
              size_t width) {
  const int min_x = imax(s.min_x, x0), max_x = imin(s.max_x, x1 - 1);
  const int min_y = imax(s.min_y, y0), max_y = imin(s.max_y, y1 - 1);
  if (min_x > max_x || min_y > max_y) return;
  constexpr int kBlock = 8;
  const int64_t one = int64_t(1) << kSubpixelBits, half = one / 2;
  const __m512i iota = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
  int64_t step_x[3], step_y[3], bstep[3], x_span[3];
  __m512i lane[3], dy[3];
  for (int k = 0; k < 3; ++k) {
    step_x[k] = s.a[k] * one;
    step_y[k] = s.b[k] * one;
    bstep[k] = step_x[k] * kBlock;
    x_span[k] = step_x[k] * (kBlock - 1);
    lane[k] = _mm512_mullo_epi64(_mm512_set1_epi64(step_x[k]), iota);
    dy[k] = _mm512_set1_epi64(step_y[k]);
  }
  const __m256 z_lo = _mm256_set1_ps(s.z_lo), z_hi = _mm256_set1_ps(s.z_hi);
  const __m256i id = _mm256_set1_epi32(int(s.triangle));
  const int bx_start = min_x - (min_x - x0) % kBlock;
  const int by_start = min_y - (min_y - y0) % kBlock;
  for (int by = by_start; by <= max_y; by += kBlock) {
    const int py0 = imax(by, min_y), py1 = imin(by + kBlock - 1, max_y);
    const PlaneRows p{s.z0, s.z_dy, py0 - s.min_y, py1 - py0 + 1};
    int64_t e[3], lo_off[3], hi_off[3];
    for (int k = 0; k < 3; ++k) {
      e[k] =
          s.a[k] * (int64_t(bx_start) * one + half) + s.b[k] * (int64_t(py0) * one + half) + s.c[k];
      const int64_t d = step_y[k] * int64_t(py1 - py0);
      lo_off[k] = min64(0, x_span[k]) + min64(0, d);
      hi_off[k] = max64(0, x_span[k]) + max64(0, d);
    }
    float* const zrow = z + size_t(py0) * width;
    uint32_t* const idrow = ids ? ids + size_t(py0) * width : nullptr;
    for (int bx = bx_start; bx <= max_x;
         bx += kBlock, e[0] += bstep[0], e[1] += bstep[1], e[2] += bstep[2]) {
      if (e[0] + hi_off[0] < 0 || e[1] + hi_off[1] < 0 || e[2] + hi_off[2] < 0) continue;
      const bool inside = e[0] + lo_off[0] >= 0 && e[1] + lo_off[1] >= 0 && e[2] + lo_off[2] >= 0;
      // The viewport's right edge: lanes from x1 on are not pixels.
      const __mmask8 lanes = bx + kBlock > x1 ? __mmask8((1u << (x1 - bx)) - 1u) : __mmask8(0xFF);
      __m512i ev[3];
      for (int k = 0; k < 3; ++k) ev[k] = _mm512_add_epi64(_mm512_set1_epi64(e[k]), lane[k]);
      block_rows(ev, dy, inside, lanes, plane_x(s.z_dx, bx - s.min_x), p, z_lo, z_hi, id, zrow + bx,
                 idrow ? idrow + bx : nullptr, width);
    }
  }
}

}  // namespace shadowlab::depth_kernels_avx512
#endif
