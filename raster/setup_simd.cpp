#include "raster/setup_simd.h"

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

#include "core/isa.h"
#include "core/simd_target.h"

namespace shadowlab {

int setup_batch8_scalar(const SetupBatch8& b, int width, int height, CullMode cull,
                        TriangleSetup* out, RasterStats& stats) {
  int n = 0;
  for (int k = 0; k < b.count; ++k) {
    ClipVertex v[3];
    for (int i = 0; i < 3; ++i) {
      v[i].clip = vec4(b.x[i][k], b.y[i][k], 0.0f, b.w[i][k]);
      v[i].bary = vec3(i == 0 ? 1.0f : 0.0f, i == 1 ? 1.0f : 0.0f, i == 2 ? 1.0f : 0.0f);
    }
    if (setup_triangle(v[0], v[1], v[2], b.triangle[k], width, height, cull, out[n], stats)) ++n;
  }
  return n;
}

#ifdef SHADOWLAB_HAVE_X86
namespace {

// A batch's lanes between the vector code and the records: the integers as int64 (AVX-512)
// or as the doubles that hold them exactly (AVX2), the plane as float or double.
template <class Int, class Real>
struct SetupLanes {
  alignas(64) Int a[3][8], b[3][8], c[3][8], area[8], x0[8], x1[8], y0[8], y1[8];
  alignas(64) Real iw[3][8], z0[8], zx[8], zy[8], lo[8], hi[8];
};

// The records of the lanes in `live` (bit k: lane k), in lane order: vertices 1 and 2 swapped
// where `neg`, edge e's bias 0 where top_left[e] has the lane, else −1. The conversions are
// exact for the integers; for the plane, float(double) is the scalar setup's own rounding.
template <class Int, class Real>
int write_setups(const SetupLanes<Int, Real>& L, int live, int neg, const int* top_left,
                 const uint32_t* triangle, TriangleSetup* out) {
  int n = 0;
  for (int k = 0; k < 8; ++k) {
    if (!((live >> k) & 1)) continue;
    TriangleSetup& s = out[n++];
    const bool swapped = (neg >> k) & 1;
    const int order[3] = {0, swapped ? 2 : 1, swapped ? 1 : 2};
    for (int e = 0; e < 3; ++e) {
      s.a[e] = int64_t(L.a[e][k]);
      s.b[e] = int64_t(L.b[e][k]);
      s.c[e] = int64_t(L.c[e][k]);
      s.bias[e] = int8_t(((top_left[e] >> k) & 1) ? 0 : -1);
      s.inv_w[e] = float(L.iw[e][k]);
      // The original vertex's unit barycentrics times its 1/w, as vec3 * float.
      const vec3 unit(order[e] == 0 ? 1.0f : 0.0f, order[e] == 1 ? 1.0f : 0.0f,
                      order[e] == 2 ? 1.0f : 0.0f);
      s.bary_over_w[e] = unit * s.inv_w[e];
    }
    s.area2 = int64_t(L.area[k]);
    s.min_x = int(L.x0[k]);
    s.max_x = int(L.x1[k]);
    s.min_y = int(L.y0[k]);
    s.max_y = int(L.y1[k]);
    s.z0 = float(L.z0[k]);
    s.z_dx = float(L.zx[k]);
    s.z_dy = float(L.zy[k]);
    s.z_lo = float(L.lo[k]);
    s.z_hi = float(L.hi[k]);
    s.triangle = triangle[k];
  }
  return n;
}

#define SL_SETUP SL_TARGET("avx512f,avx512dq,avx512vl")

// The zero-masked forms with every lane on: GCC 12's unmasked ones pass an undefined source
// that -Wmaybe-uninitialized reports (the same instructions).
SL_SETUP inline __m512d widen(const float* p) {
  return _mm512_maskz_cvtps_pd(0xFF, _mm256_load_ps(p));
}
SL_SETUP inline __m512i round_to_int64(__m512d v) {
  return _mm512_maskz_cvtpd_epi64(0xFF, v);  // current rounding mode: llrint's
}
SL_SETUP inline __m256 narrow(__m512d v) { return _mm512_maskz_cvtpd_ps(0xFF, v); }
SL_SETUP inline __m512i sra8(__m512i a, unsigned n) { return _mm512_maskz_srai_epi64(0xFF, a, n); }
SL_SETUP inline __m512i min64(__m512i a, __m512i b) { return _mm512_maskz_min_epi64(0xFF, a, b); }
SL_SETUP inline __m512i max64(__m512i a, __m512i b) { return _mm512_maskz_max_epi64(0xFF, a, b); }
// ceil_div(a, 256) = −floor_div(−a, 256), and floor division by 256 is an arithmetic shift.
SL_SETUP inline __m512i ceil256(__m512i a) {
  const __m512i zero = _mm512_setzero_si512();
  return _mm512_sub_epi64(zero, sra8(_mm512_sub_epi64(zero, a), kSubpixelBits));
}

SL_SETUP int setup_batch8_avx512(const SetupBatch8& b, int width, int height, CullMode cull,
                                 TriangleSetup* out, RasterStats& stats) {
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
  const __m512i max_x = min64(_mm512_set1_epi64(width - 1),
                                         sra8(_mm512_sub_epi64(hi_x, half), kSubpixelBits));
  const __m512i min_y = max64(zero, ceil256(_mm512_sub_epi64(lo_y, half)));
  const __m512i max_y = min64(_mm512_set1_epi64(height - 1),
                                         sra8(_mm512_sub_epi64(hi_y, half), kSubpixelBits));
  const __mmask8 empty = __mmask8(live & (_mm512_cmpgt_epi64_mask(min_x, max_x) |
                                          _mm512_cmpgt_epi64_mask(min_y, max_y)));
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
  const __m256 z0 = narrow(
      _mm512_add_pd(_mm512_add_pd(iw0, _mm512_mul_pd(dzdx, px)), _mm512_mul_pd(dzdy, py)));
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

#undef SL_SETUP

// The AVX2 form: the same operations in double, two halves of 4 lanes. AVX2 has no int64
// multiply, conversion, shift or min/max, so the snapped coordinates stay in double: they are
// integers, and while every |fx|, |fy| < 2^24 (the viewport plus the 16384-pixel guard band is
// 2^15 pixels wide at res 16384, 2^23 sub-pixel units) the differences (< 2^25), the area and
// the edge constants (< 2^51) are exact in double, so each value equals setup_triangle's int64
// one. A batch with a coordinate outside that range (or not finite) goes through the scalar
// setup whole.
#define SL_SETUP2 SL_TARGET("avx2")

// Lane arrays of one batch between the vector halves and the records.
struct SetupLanes8 : SetupLanes<double, double> {
  int degenerate = 0, culled = 0, live = 0, neg = 0, top_left[3] = {};
};

SL_SETUP2 inline __m256d blend(__m256d mask, __m256d if_clear, __m256d if_set) {
  return _mm256_blendv_pd(if_clear, if_set, mask);
}

SL_SETUP2 inline __m256d lo3(const __m256d* v) {
  return _mm256_min_pd(_mm256_min_pd(v[0], v[1]), v[2]);
}
SL_SETUP2 inline __m256d hi3(const __m256d* v) {
  return _mm256_max_pd(_mm256_max_pd(v[0], v[1]), v[2]);
}

// Lanes 4h .. 4h + 3 of the batch into L; returns false when a coordinate leaves the exact
// range (the caller then takes the scalar setup for the whole batch).
SL_SETUP2 bool setup_half_avx2(const SetupBatch8& b, int h, int width, int height, CullMode cull,
                               SetupLanes8& L) {
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
        _mm256_add_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_cvtps_pd(_mm_load_ps(b.x[i] + o)), inv_w),
                                    half_d),
                      half_d),
        wd);
    sy[i] = _mm256_mul_pd(
        _mm256_sub_pd(half_d,
                      _mm256_mul_pd(_mm256_mul_pd(_mm256_cvtps_pd(_mm_load_ps(b.y[i] + o)), inv_w),
                                    half_d)),
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
  __m256d area2 = _mm256_sub_pd(
      _mm256_mul_pd(_mm256_sub_pd(fx[1], fx[0]), _mm256_sub_pd(fy[2], fy[0])),
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
    _mm256_store_pd(L.c[k] + o,
                    _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(dy, X[i]), _mm256_mul_pd(dx, Y[i])),
                                  bias));
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
  const int empty = live & _mm256_movemask_pd(_mm256_or_pd(
                               _mm256_cmp_pd(min_x, max_x, _CMP_GT_OQ),
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

SL_SETUP2 int setup_batch8_avx2(const SetupBatch8& b, int width, int height, CullMode cull,
                                TriangleSetup* out, RasterStats& stats) {
  SetupLanes8 L;
  if (!setup_half_avx2(b, 0, width, height, cull, L) ||
      !setup_half_avx2(b, 1, width, height, cull, L))
    return setup_batch8_scalar(b, width, height, cull, out, stats);
  stats.dropped_degenerate += size_t(__builtin_popcount(unsigned(L.degenerate)));
  stats.culled_facing += size_t(__builtin_popcount(unsigned(L.culled)));
  return write_setups(L, L.live, L.neg, L.top_left, b.triangle, out);
}

#undef SL_SETUP2

}  // namespace
#endif

SetupBatch8Fn setup_batch8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (process_isa() == Isa::avx512) return setup_batch8_avx512;
  if (process_isa() >= Isa::avx2) return setup_batch8_avx2;
#endif
  return nullptr;
}

SetupBatch8Fn setup_batch8_avx2_form() {
#ifdef SHADOWLAB_HAVE_X86
  if (cpu_isa() >= Isa::avx2) return setup_batch8_avx2;
#endif
  return nullptr;
}

}  // namespace shadowlab

// File-local: a unity build compiles the next file in the same translation unit.
#undef SHADOWLAB_HAVE_X86
