// The AVX2 form of raster/setup_simd.h: double lanes, two halves of 4. Compiled with -mavx2
// -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

#include "raster/setup_simd.h"
#include "raster/setup_simd_lanes.h"

namespace shadowlab::setup_simd_avx2 {

// The AVX2 form: the same operations in double, two halves of 4 lanes. AVX2 has no int64
// multiply, conversion, shift or min/max, so the snapped coordinates stay in double: they are
// integers, and while every |fx|, |fy| < 2^24 (the viewport plus the 16384-pixel guard band is
// 2^15 pixels wide at res 16384, 2^23 sub-pixel units) the differences (< 2^25), the area and
// the edge constants (< 2^51) are exact in double, so each value equals setup_triangle's int64
// one. A batch with a coordinate outside that range (or not finite) goes through the scalar
// setup whole.
// Lane arrays of one batch between the vector halves and the records.
struct SetupLanes8 : SetupLanes<double, double> {
  int degenerate = 0, culled = 0, live = 0, neg = 0, top_left[3] = {};
};

[[gnu::always_inline]] inline __m256d blend(__m256d mask, __m256d if_clear, __m256d if_set) {
  return _mm256_blendv_pd(if_clear, if_set, mask);
}

[[gnu::always_inline]] inline __m256d lo3(const __m256d* v) {
  return _mm256_min_pd(_mm256_min_pd(v[0], v[1]), v[2]);
}
[[gnu::always_inline]] inline __m256d hi3(const __m256d* v) {
  return _mm256_max_pd(_mm256_max_pd(v[0], v[1]), v[2]);
}

// Lanes 4h .. 4h + 3 of the batch into L; returns false when a coordinate leaves the exact
// range (the caller then takes the scalar setup for the whole batch).
bool setup_half(const SetupBatch8& b, int h, int width, int height, CullMode cull, SetupLanes8& L) {
  const int o = 4 * h;
  const int active = b.count - o >= 4 ? 0xF : b.count > o ? (1 << (b.count - o)) - 1 : 0;
  if (!active) return true;
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0);
  const __m256d half_d = _mm256_set1_pd(0.5);
  const __m256d wd = _mm256_set1_pd(double(width)), hd = _mm256_set1_pd(double(height));
  const __m256d sub_one = _mm256_set1_pd(double(kSubpixelOne));
  const __m256d limit = _mm256_set1_pd(16777216.0);  // 2^24
  const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FFFFFFFFFFFFFFF));
  __m256d sx[3], sy[3], fx[3], fy[3], iwf[3];
  int in_range = 0xF;
  for (int i = 0; i < 3; ++i) {
    const __m256d w = _mm256_cvtps_pd(_mm_load_ps(b.w[i] + o));
    const __m256d inv_w = _mm256_div_pd(one, w);
    sx[i] = _mm256_mul_pd(
        _mm256_add_pd(
            _mm256_mul_pd(_mm256_mul_pd(_mm256_cvtps_pd(_mm_load_ps(b.x[i] + o)), inv_w), half_d),
            half_d),
        wd);
    sy[i] = _mm256_mul_pd(
        _mm256_sub_pd(
            half_d,
            _mm256_mul_pd(_mm256_mul_pd(_mm256_cvtps_pd(_mm_load_ps(b.y[i] + o)), inv_w), half_d)),
        hd);
    // llrint in the default rounding mode: to nearest, ties to even.
    constexpr int kNearest = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
    fx[i] = _mm256_round_pd(_mm256_mul_pd(sx[i], sub_one), kNearest);
    fy[i] = _mm256_round_pd(_mm256_mul_pd(sy[i], sub_one), kNearest);
    in_range &= _mm256_movemask_pd(
        _mm256_and_pd(_mm256_cmp_pd(_mm256_and_pd(fx[i], abs_mask), limit, _CMP_LT_OQ),
                      _mm256_cmp_pd(_mm256_and_pd(fy[i], abs_mask), limit, _CMP_LT_OQ)));
    // 1/w in float, widened (exact): compared and stored as setup_triangle's float.
    iwf[i] = _mm256_cvtps_pd(_mm_div_ps(_mm_set1_ps(1.0f), _mm_load_ps(b.w[i] + o)));
  }
  if ((in_range & active) != active) return false;
  __m256d area2 =
      _mm256_sub_pd(_mm256_mul_pd(_mm256_sub_pd(fx[1], fx[0]), _mm256_sub_pd(fy[2], fy[0])),
                    _mm256_mul_pd(_mm256_sub_pd(fy[1], fy[0]), _mm256_sub_pd(fx[2], fx[0])));
  const int degenerate = active & _mm256_movemask_pd(_mm256_cmp_pd(area2, zero, _CMP_EQ_OQ));
  const __m256d negv = _mm256_cmp_pd(area2, zero, _CMP_LT_OQ);  // front-facing (y flip)
  const int neg = _mm256_movemask_pd(negv);
  int culled = 0;
  if (cull == CullMode::Back) culled = active & ~degenerate & ~neg;
  if (cull == CullMode::Front) culled = active & ~degenerate & neg;
  int live = active & ~degenerate & ~culled;
  // Orientation: vertices 1 and 2 swap where the area is negative.
  area2 = blend(negv, area2, _mm256_sub_pd(zero, area2));
  const __m256d X[3] = {fx[0], blend(negv, fx[1], fx[2]), blend(negv, fx[2], fx[1])};
  const __m256d Y[3] = {fy[0], blend(negv, fy[1], fy[2]), blend(negv, fy[2], fy[1])};
  const __m256d SX[3] = {sx[0], blend(negv, sx[1], sx[2]), blend(negv, sx[2], sx[1])};
  const __m256d SY[3] = {sy[0], blend(negv, sy[1], sy[2]), blend(negv, sy[2], sy[1])};
  const __m256d IW[3] = {iwf[0], blend(negv, iwf[1], iwf[2]), blend(negv, iwf[2], iwf[1])};
  // Edges: a = −dy, b = dx, c = dy·x_i − dx·y_i + bias, bias 0 on top-left edges, else −1.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const __m256d dx = _mm256_sub_pd(X[j], X[i]), dy = _mm256_sub_pd(Y[j], Y[i]);
    const __m256d tl = _mm256_or_pd(
        _mm256_and_pd(_mm256_cmp_pd(dy, zero, _CMP_EQ_OQ), _mm256_cmp_pd(dx, zero, _CMP_GT_OQ)),
        _mm256_cmp_pd(dy, zero, _CMP_LT_OQ));
    L.top_left[k] |= _mm256_movemask_pd(tl) << o;
    const __m256d bias = blend(tl, _mm256_set1_pd(-1.0), zero);
    _mm256_store_pd(L.a[k] + o, _mm256_sub_pd(zero, dy));
    _mm256_store_pd(L.b[k] + o, dx);
    _mm256_store_pd(
        L.c[k] + o,
        _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(dy, X[i]), _mm256_mul_pd(dx, Y[i])), bias));
  }
  // Covered-pixel bounds: pixel x covers sample 256·x + 128 (divisions by 256 exact).
  const __m256d half = _mm256_set1_pd(double(kSubpixelOne / 2));
  const __m256d inv_one = _mm256_set1_pd(1.0 / double(kSubpixelOne));
  constexpr int kUp = _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC;
  constexpr int kDown = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
  const __m256d min_x = _mm256_max_pd(
      zero, _mm256_round_pd(_mm256_mul_pd(_mm256_sub_pd(lo3(X), half), inv_one), kUp));
  const __m256d max_x =
      _mm256_min_pd(_mm256_set1_pd(double(width - 1)),
                    _mm256_round_pd(_mm256_mul_pd(_mm256_sub_pd(hi3(X), half), inv_one), kDown));
  const __m256d min_y = _mm256_max_pd(
      zero, _mm256_round_pd(_mm256_mul_pd(_mm256_sub_pd(lo3(Y), half), inv_one), kUp));
  const __m256d max_y =
      _mm256_min_pd(_mm256_set1_pd(double(height - 1)),
                    _mm256_round_pd(_mm256_mul_pd(_mm256_sub_pd(hi3(Y), half), inv_one), kDown));
  const int empty =
      live & _mm256_movemask_pd(_mm256_or_pd(_mm256_cmp_pd(min_x, max_x, _CMP_GT_OQ),
                                             _mm256_cmp_pd(min_y, max_y, _CMP_GT_OQ)));
  live &= ~empty;
  L.degenerate |= (degenerate | empty) << o;
  L.culled |= culled << o;
  L.live |= live << o;
  L.neg |= (neg & active) << o;
  if (!live) return true;
  _mm256_store_pd(L.area + o, area2);
  _mm256_store_pd(L.x0 + o, min_x);
  _mm256_store_pd(L.x1 + o, max_x);
  _mm256_store_pd(L.y0 + o, min_y);
  _mm256_store_pd(L.y1 + o, max_y);
  // Plane of 1/w through the unsnapped vertices, in double.
  const __m256d x10 = _mm256_sub_pd(SX[1], SX[0]), y10 = _mm256_sub_pd(SY[1], SY[0]);
  const __m256d x20 = _mm256_sub_pd(SX[2], SX[0]), y20 = _mm256_sub_pd(SY[2], SY[0]);
  const __m256d z10 = _mm256_sub_pd(IW[1], IW[0]), z20 = _mm256_sub_pd(IW[2], IW[0]);
  const __m256d det = _mm256_sub_pd(_mm256_mul_pd(x10, y20), _mm256_mul_pd(y10, x20));
  const __m256d det_ok = _mm256_cmp_pd(det, zero, _CMP_NEQ_UQ);
  const __m256d dzdx = _mm256_and_pd(
      det_ok, _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(z10, y20), _mm256_mul_pd(z20, y10)), det));
  const __m256d dzdy = _mm256_and_pd(
      det_ok, _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(z20, x10), _mm256_mul_pd(z10, x20)), det));
  const __m256d px = _mm256_sub_pd(_mm256_add_pd(min_x, half_d), SX[0]);
  const __m256d py = _mm256_sub_pd(_mm256_add_pd(min_y, half_d), SY[0]);
  _mm256_store_pd(L.z0 + o, _mm256_add_pd(_mm256_add_pd(IW[0], _mm256_mul_pd(dzdx, px)),
                                          _mm256_mul_pd(dzdy, py)));
  _mm256_store_pd(L.zx + o, dzdx);
  _mm256_store_pd(L.zy + o, dzdy);
  // std::min({a, b, c}) and std::max: the first extreme value, strict comparisons.
  __m256d z_lo = IW[0], z_hi = IW[0];
  for (int i = 1; i < 3; ++i) {
    z_lo = blend(_mm256_cmp_pd(IW[i], z_lo, _CMP_LT_OQ), z_lo, IW[i]);
    z_hi = blend(_mm256_cmp_pd(z_hi, IW[i], _CMP_LT_OQ), z_hi, IW[i]);
  }
  _mm256_store_pd(L.lo + o, z_lo);
  _mm256_store_pd(L.hi + o, z_hi);
  for (int k = 0; k < 3; ++k) _mm256_store_pd(L.iw[k] + o, IW[k]);
  return true;
}

int batch8(const SetupBatch8& b, int width, int height, CullMode cull, TriangleSetup* out,
           RasterStats& stats) {
  SetupLanes8 L;
  if (!setup_half(b, 0, width, height, cull, L) || !setup_half(b, 1, width, height, cull, L))
    return setup_batch8_scalar(b, width, height, cull, out, stats);
  stats.dropped_degenerate += size_t(__builtin_popcount(unsigned(L.degenerate)));
  stats.culled_facing += size_t(__builtin_popcount(unsigned(L.culled)));
  return write_setups(L, L.live, L.neg, L.top_left, b.triangle, out);
}

}  // namespace shadowlab::setup_simd_avx2
#endif
