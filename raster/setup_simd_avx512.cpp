// The AVX-512 form of raster/setup_simd.h: int64 and double lanes, compare masks. Compiled with
// -mavx512f -mavx512vl -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

#include "raster/setup_simd.h"
#include "raster/setup_simd_lanes.h"

namespace shadowlab::setup_simd_avx512 {

// The zero-masked forms with every lane on: GCC 12's unmasked ones pass an undefined source
// that -Wmaybe-uninitialized reports (the same instructions).
[[gnu::always_inline]] inline __m512d widen(const float* p) {
  return _mm512_maskz_cvtps_pd(0xFF, _mm256_load_ps(p));
}
[[gnu::always_inline]] inline __m512i round_to_int64(__m512d v) {
  return _mm512_maskz_cvtpd_epi64(0xFF, v);  // current rounding mode: llrint's
}
[[gnu::always_inline]] inline __m256 narrow(__m512d v) { return _mm512_maskz_cvtpd_ps(0xFF, v); }
[[gnu::always_inline]] inline __m512i sra8(__m512i a, unsigned n) {
  return _mm512_maskz_srai_epi64(0xFF, a, n);
}
[[gnu::always_inline]] inline __m512i min64(__m512i a, __m512i b) {
  return _mm512_maskz_min_epi64(0xFF, a, b);
}
[[gnu::always_inline]] inline __m512i max64(__m512i a, __m512i b) {
  return _mm512_maskz_max_epi64(0xFF, a, b);
}
// ceil_div(a, 256) = −floor_div(−a, 256), and floor division by 256 is an arithmetic shift.
[[gnu::always_inline]] inline __m512i ceil256(__m512i a) {
  const __m512i zero = _mm512_setzero_si512();
  return _mm512_sub_epi64(zero, sra8(_mm512_sub_epi64(zero, a), kSubpixelBits));
}

int batch8(const SetupBatch8& b, int width, int height, CullMode cull, TriangleSetup* out,
           RasterStats& stats) {
  const __mmask8 active = __mmask8((1u << b.count) - 1u);
  const __m512d one = _mm512_set1_pd(1.0), half_d = _mm512_set1_pd(0.5);
  const __m512d wd = _mm512_set1_pd(double(width)), hd = _mm512_set1_pd(double(height));
  const __m512d sub_one = _mm512_set1_pd(double(kSubpixelOne));
  // Per vertex: the viewport transform in double and the fixed-point snap (setup_triangle's
  // first loop).
  __m512d sx[3], sy[3];
  __m512i fx[3], fy[3];
  __m256 iwf[3];  // 1/w in float, per original vertex
  for (int i = 0; i < 3; ++i) {
    const __m512d inv_w = _mm512_div_pd(one, widen(b.w[i]));
    sx[i] = _mm512_mul_pd(
        _mm512_add_pd(_mm512_mul_pd(_mm512_mul_pd(widen(b.x[i]), inv_w), half_d), half_d), wd);
    sy[i] = _mm512_mul_pd(
        _mm512_sub_pd(half_d, _mm512_mul_pd(_mm512_mul_pd(widen(b.y[i]), inv_w), half_d)), hd);
    fx[i] = round_to_int64(_mm512_mul_pd(sx[i], sub_one));
    fy[i] = round_to_int64(_mm512_mul_pd(sy[i], sub_one));
    iwf[i] = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_load_ps(b.w[i]));
  }
  const __m512i zero = _mm512_setzero_si512();
  __m512i area2 = _mm512_sub_epi64(
      _mm512_mullo_epi64(_mm512_sub_epi64(fx[1], fx[0]), _mm512_sub_epi64(fy[2], fy[0])),
      _mm512_mullo_epi64(_mm512_sub_epi64(fy[1], fy[0]), _mm512_sub_epi64(fx[2], fx[0])));
  const __mmask8 degenerate = _mm512_mask_cmpeq_epi64_mask(active, area2, zero);
  const __mmask8 neg = _mm512_cmplt_epi64_mask(area2, zero);  // front-facing (y flip)
  __mmask8 culled = 0;
  if (cull == CullMode::Back) culled = __mmask8(active & ~degenerate & ~neg);
  if (cull == CullMode::Front) culled = __mmask8(active & ~degenerate & neg);
  __mmask8 live = __mmask8(active & ~degenerate & ~culled);
  // Orientation: vertices 1 and 2 swap where the area is negative.
  area2 = _mm512_mask_sub_epi64(area2, neg, zero, area2);
  const __m512i X[3] = {fx[0], _mm512_mask_blend_epi64(neg, fx[1], fx[2]),
                        _mm512_mask_blend_epi64(neg, fx[2], fx[1])};
  const __m512i Y[3] = {fy[0], _mm512_mask_blend_epi64(neg, fy[1], fy[2]),
                        _mm512_mask_blend_epi64(neg, fy[2], fy[1])};
  const __m512d SX[3] = {sx[0], _mm512_mask_blend_pd(neg, sx[1], sx[2]),
                         _mm512_mask_blend_pd(neg, sx[2], sx[1])};
  const __m512d SY[3] = {sy[0], _mm512_mask_blend_pd(neg, sy[1], sy[2]),
                         _mm512_mask_blend_pd(neg, sy[2], sy[1])};
  const __m256 IW[3] = {iwf[0], _mm256_mask_blend_ps(neg, iwf[1], iwf[2]),
                        _mm256_mask_blend_ps(neg, iwf[2], iwf[1])};
  // Edges: a = −dy, b = dx, c = dy·x_i − dx·y_i + bias, bias 0 on top-left edges, else −1.
  __m512i ea[3], eb[3], ec[3];
  __mmask8 top_left[3];
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const __m512i dx = _mm512_sub_epi64(X[j], X[i]), dy = _mm512_sub_epi64(Y[j], Y[i]);
    ea[k] = _mm512_sub_epi64(zero, dy);
    eb[k] = dx;
    top_left[k] = __mmask8((_mm512_cmpeq_epi64_mask(dy, zero) & _mm512_cmpgt_epi64_mask(dx, zero)) |
                           _mm512_cmplt_epi64_mask(dy, zero));
    const __m512i bias = _mm512_mask_blend_epi64(top_left[k], _mm512_set1_epi64(-1), zero);
    ec[k] = _mm512_add_epi64(
        _mm512_sub_epi64(_mm512_mullo_epi64(dy, X[i]), _mm512_mullo_epi64(dx, Y[i])), bias);
  }
  // Covered-pixel bounds: pixel x covers sample 256·x + 128; floor division by 256 is an
  // arithmetic shift, ceil_div(a, 256) = −((−a) >> 8).
  const __m512i half = _mm512_set1_epi64(kSubpixelOne / 2);
  const __m512i lo_x = min64(min64(X[0], X[1]), X[2]);
  const __m512i hi_x = max64(max64(X[0], X[1]), X[2]);
  const __m512i lo_y = min64(min64(Y[0], Y[1]), Y[2]);
  const __m512i hi_y = max64(max64(Y[0], Y[1]), Y[2]);
  const __m512i min_x = max64(zero, ceil256(_mm512_sub_epi64(lo_x, half)));
  const __m512i max_x =
      min64(_mm512_set1_epi64(width - 1), sra8(_mm512_sub_epi64(hi_x, half), kSubpixelBits));
  const __m512i min_y = max64(zero, ceil256(_mm512_sub_epi64(lo_y, half)));
  const __m512i max_y =
      min64(_mm512_set1_epi64(height - 1), sra8(_mm512_sub_epi64(hi_y, half), kSubpixelBits));
  const __mmask8 empty = __mmask8(
      live & (_mm512_cmpgt_epi64_mask(min_x, max_x) | _mm512_cmpgt_epi64_mask(min_y, max_y)));
  live = __mmask8(live & ~empty);
  stats.dropped_degenerate += size_t(__builtin_popcount(degenerate | empty));
  stats.culled_facing += size_t(__builtin_popcount(culled));
  if (!live) return 0;
  // Plane of 1/w through the unsnapped vertices, in double.
  const __m512d x10 = _mm512_sub_pd(SX[1], SX[0]), y10 = _mm512_sub_pd(SY[1], SY[0]);
  const __m512d x20 = _mm512_sub_pd(SX[2], SX[0]), y20 = _mm512_sub_pd(SY[2], SY[0]);
  const __m512d iw0 = _mm512_maskz_cvtps_pd(0xFF, IW[0]);
  const __m512d z10 = _mm512_sub_pd(_mm512_maskz_cvtps_pd(0xFF, IW[1]), iw0);
  const __m512d z20 = _mm512_sub_pd(_mm512_maskz_cvtps_pd(0xFF, IW[2]), iw0);
  const __m512d det = _mm512_sub_pd(_mm512_mul_pd(x10, y20), _mm512_mul_pd(y10, x20));
  const __mmask8 det_ok = _mm512_cmp_pd_mask(det, _mm512_setzero_pd(), _CMP_NEQ_UQ);
  const __m512d dzdx = _mm512_maskz_div_pd(
      det_ok, _mm512_sub_pd(_mm512_mul_pd(z10, y20), _mm512_mul_pd(z20, y10)), det);
  const __m512d dzdy = _mm512_maskz_div_pd(
      det_ok, _mm512_sub_pd(_mm512_mul_pd(z20, x10), _mm512_mul_pd(z10, x20)), det);
  const __m512d px =
      _mm512_sub_pd(_mm512_add_pd(_mm512_maskz_cvtepi64_pd(0xFF, min_x), half_d), SX[0]);
  const __m512d py =
      _mm512_sub_pd(_mm512_add_pd(_mm512_maskz_cvtepi64_pd(0xFF, min_y), half_d), SY[0]);
  const __m256 z0 =
      narrow(_mm512_add_pd(_mm512_add_pd(iw0, _mm512_mul_pd(dzdx, px)), _mm512_mul_pd(dzdy, py)));
  // std::min({a, b, c}) and std::max: the first extreme value, strict comparisons.
  __m256 z_lo = IW[0], z_hi = IW[0];
  for (int i = 1; i < 3; ++i) {
    z_lo = _mm256_mask_blend_ps(_mm256_cmp_ps_mask(IW[i], z_lo, _CMP_LT_OQ), z_lo, IW[i]);
    z_hi = _mm256_mask_blend_ps(_mm256_cmp_ps_mask(z_hi, IW[i], _CMP_LT_OQ), z_hi, IW[i]);
  }
  // Lanes out to memory, then the surviving triangles' records in lane order.
  SetupLanes<int64_t, float> L;
  for (int k = 0; k < 3; ++k) {
    _mm512_store_si512(L.a[k], ea[k]);
    _mm512_store_si512(L.b[k], eb[k]);
    _mm512_store_si512(L.c[k], ec[k]);
    _mm256_store_ps(L.iw[k], IW[k]);
  }
  _mm512_store_si512(L.area, area2);
  _mm512_store_si512(L.x0, min_x);
  _mm512_store_si512(L.x1, max_x);
  _mm512_store_si512(L.y0, min_y);
  _mm512_store_si512(L.y1, max_y);
  _mm256_store_ps(L.z0, z0);
  _mm256_store_ps(L.zx, narrow(dzdx));
  _mm256_store_ps(L.zy, narrow(dzdy));
  _mm256_store_ps(L.lo, z_lo);
  _mm256_store_ps(L.hi, z_hi);
  const int tl[3] = {top_left[0], top_left[1], top_left[2]};
  return write_setups(L, live, neg, tl, b.triangle, out);
}

}  // namespace shadowlab::setup_simd_avx512
#endif
