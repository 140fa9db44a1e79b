// The AVX2 table of techniques/lookup/lookup_batches.h: each filter's lookup arithmetic for a batch of
// 8 pixels in AVX2 lanes (8 floats, or two halves of 4 doubles). Compiled with -mavx2 -mfma
// (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstdint>

#include "core/exp_log_avx2.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/lookup/map_lookup_simd.h"
#include "techniques/filters/msm/moment_bound.h"

namespace shadowlab::lookup_batches_avx2 {

using namespace exp_log_avx2;

#include "techniques/filters/moments_common/chebyshev_avx2.inl"
#include "techniques/filters/msm/moment_bound_avx2.inl"
#include "techniques/lookup/tap_avx2.inl"

// ESM: esm_combine (exponential_map.cpp) in 8 lanes, the same operations in the same order
// (exp_f8: exp_f's steps; std::min(a, b) is b < a ? b : a, i.e. _mm256_min_ps(b, a)).
void esm_combine8(const float (*z)[8], const float* fx, const float* fy, const float* ct,
                  float* out) {
  const __m256 vct = _mm256_loadu_ps(ct), one = _mm256_set1_ps(1.0f);
  __m256 e[4];
  for (int i = 0; i < 4; ++i) {
    const __m256 d = _mm256_sub_ps(_mm256_loadu_ps(z[i]), vct);
    e[i] = exp_f8(_mm256_max_ps(_mm256_set1_ps(-87.0f), _mm256_min_ps(_mm256_set1_ps(80.0f), d)));
  }
  const __m256 vx = _mm256_loadu_ps(fx), vy = _mm256_loadu_ps(fy);
  const __m256 ox = _mm256_sub_ps(one, vx), oy = _mm256_sub_ps(one, vy);
  const __m256 v = _mm256_add_ps(
      _mm256_mul_ps(oy, _mm256_add_ps(_mm256_mul_ps(ox, e[0]), _mm256_mul_ps(vx, e[1]))),
      _mm256_mul_ps(vy, _mm256_add_ps(_mm256_mul_ps(ox, e[2]), _mm256_mul_ps(vx, e[3]))));
  _mm256_storeu_ps(out, _mm256_min_ps(one, v));
}

// VSM: vsm_value (centred moments, not fp32) for 4 lanes in double: its operations in its order
// (std::max(a, b) is a < b ? b : a, a blend on that compare; std::clamp likewise), so the lanes
// get vsm_value's bits.
__m256d vsm_value4(const VsmLookupConsts& k, const __m256d* A, const __m256d* B,
                   const __m256* M4, __m256d fx, __m256d fy, __m256d t, __m256d active,
                   int half) {
  const __m256d zero = _mm256_setzero_pd();
  __m256d w[4];
  bilinear_weights4(fx, fy, w);
  // When every active lane has t <= μ, chebyshev4 gives 1 on each of them: skip the variance
  // and the division (most batches of a scene are lit). A NaN lane fails t <= μ and takes the
  // full path, as do batches with any shadowed lane; inactive lanes' results are unused.
  const __m256d mean = mixture_mean4(w, A);
  __m256d result;
  if (_mm256_movemask_pd(_mm256_or_pd(_mm256_cmp_pd(t, mean, _CMP_LE_OQ),
                                      _mm256_xor_pd(active, _mm256_castsi256_pd(
                                                                _mm256_set1_epi64x(-1))))) == 0xF) {
    result = _mm256_set1_pd(1.0);
  } else {
    const __m256d var = mixture_variance4(w, A, B, mean);
    result = chebyshev4(t, mean, var, _mm256_set1_pd(k.min_var), k.bleed);
  }
  if (k.maxdepth) {
    // m = max(max(M0, M1), max(M2, M3)) in float, then t > m + eps → 0.
    const __m256 m01 = _mm256_blendv_ps(M4[0], M4[1], _mm256_cmp_ps(M4[0], M4[1], _CMP_LT_OQ));
    const __m256 m23 = _mm256_blendv_ps(M4[2], M4[3], _mm256_cmp_ps(M4[2], M4[3], _CMP_LT_OQ));
    const __m256 m8 = _mm256_blendv_ps(m01, m23, _mm256_cmp_ps(m01, m23, _CMP_LT_OQ));
    const __m256d m =
        _mm256_cvtps_pd(half ? _mm256_extractf128_ps(m8, 1) : _mm256_castps256_ps128(m8));
    result = _mm256_blendv_pd(
        result, zero, _mm256_cmp_pd(t, _mm256_add_pd(m, _mm256_set1_pd(k.eps)), _CMP_GT_OQ));
  }
  return result;
}

// The 8 lanes of a batch: two halves of vsm_value4.
void vsm_batch(const VsmLookupConsts& k, const float (*v)[4][8], const float* fx, const float* fy,
               const float* depth, const int32_t* active, float* out) {
  __m256 M4[4];
  for (int i = 0; i < 4; ++i) M4[i] = _mm256_load_ps(v[2][i]);
  for (int half = 0; half < 2; ++half) {
    __m256d A[4], B[4];
    for (int i = 0; i < 4; ++i) {
      A[i] = _mm256_cvtps_pd(_mm_load_ps(v[0][i] + 4 * half));
      B[i] = _mm256_cvtps_pd(_mm_load_ps(v[1][i] + 4 * half));
    }
    const __m256d res =
        vsm_value4(k, A, B, M4, _mm256_cvtps_pd(_mm_loadu_ps(fx + 4 * half)),
                   _mm256_cvtps_pd(_mm_loadu_ps(fy + 4 * half)),
                   _mm256_cvtps_pd(_mm_loadu_ps(depth + 4 * half)),
                   _mm256_castsi256_pd(_mm256_cvtepi32_epi64(
                       _mm_loadu_si128(reinterpret_cast<const __m128i*>(active + 4 * half)))),
                   half);
    _mm_storeu_ps(out + 4 * half, _mm256_cvtpd_ps(res));
  }
}

// EVSM: warp_bound for 4 lanes in double: its operations in its order (std::max(a, b) is
// a < b ? b : a, std::clamp likewise; exp_d4 gives exp_d's bits), so the lanes get warp_bound's
// bits before the final rounding to float.
__m256d warp_bound4(const EvsmLookupConsts& k, const __m256d* w, const __m256d* A,
                    const __m256d* B, __m256d t, double c, double sign) {
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d x = _mm256_mul_pd(_mm256_set1_pd(sign * c),
                                  _mm256_sub_pd(_mm256_mul_pd(_mm256_set1_pd(2.0), t), one));
  const __m256d e = exp_d4(x);
  const __m256d slope = _mm256_mul_pd(_mm256_set1_pd(2.0 * c), e);
  __m256d mean, var;
  mixture_moments4(w, A, B, mean, var);
  const __m256d min_var = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(k.min_var), slope), slope);
  return chebyshev4(_mm256_mul_pd(_mm256_set1_pd(sign), e), mean, var, min_var, k.bleed);
}

// evsm_value for the 8 lanes of a batch, in two halves of 4 doubles.
void evsm_batch(const EvsmLookupConsts& k, const float (*v)[4][8], const float* fx,
                const float* fy, const float* depth, float* out) {
  for (int half = 0; half < 2; ++half) {
    const __m256d vx = _mm256_cvtps_pd(_mm_loadu_ps(fx + 4 * half));
    const __m256d vy = _mm256_cvtps_pd(_mm_loadu_ps(fy + 4 * half));
    __m256d w[4];
    bilinear_weights4(vx, vy, w);
    const __m256d t = _mm256_cvtps_pd(_mm_loadu_ps(depth + 4 * half));
    __m256d A[4], B[4];
    for (int i = 0; i < 4; ++i) {
      A[i] = _mm256_cvtps_pd(_mm_load_ps(v[0][i] + 4 * half));
      B[i] = _mm256_cvtps_pd(_mm_load_ps(v[1][i] + 4 * half));
    }
    __m128 res = _mm256_cvtpd_ps(warp_bound4(k, w, A, B, t, k.c_pos, 1.0));
    if (k.four) {
      for (int i = 0; i < 4; ++i) {
        A[i] = _mm256_cvtps_pd(_mm_load_ps(v[2][i] + 4 * half));
        B[i] = _mm256_cvtps_pd(_mm_load_ps(v[3][i] + 4 * half));
      }
      // std::min(pos, neg) = neg < pos ? neg : pos.
      res = _mm_min_ps(_mm256_cvtpd_ps(warp_bound4(k, w, A, B, t, k.c_neg, -1.0)), res);
    }
    _mm_storeu_ps(out + 4 * half, res);
  }
}

// MSM: msm_value for the 8 lanes of each of N batches, from their bilinearly mixed moments
// (bilinear8_mix4: msm_value's sum, bit for bit), each batch in two halves of 4 doubles:
// msm_value's remaining operations in its order, the 2N halves' reconstructions side by side
// (msm_intensity4n<2N>: N > 1 overlaps the batches' chains of divisions).
template <int N>
void msm_mixed(const MsmLookupConsts& k, const double (*const* mixed)[8],
               const float* const* depth, float* const* out) {
  const __m256d one = _mm256_set1_pd(1.0);
  __m256d m[2 * N][4], z[2 * N], g[2 * N];
  for (int hh = 0; hh < 2 * N; ++hh) {
    const int h = hh / 2, half = hh % 2;
    __m256d* mh = m[hh];
    for (int j = 0; j < 4; ++j) mh[j] = _mm256_load_pd(mixed[h][j] + 4 * half);
    if (k.quantize16) {
      // msm_decode16's operations, lane by lane.
      const __m256d q[4] = {_mm256_sub_pd(mh[0], _mm256_set1_pd(kMsmOffset)), mh[1], mh[2],
                            mh[3]};
      for (int j = 0; j < 4; ++j) {
        __m256d s = _mm256_mul_pd(q[0], _mm256_set1_pd(kMsmInverse[0][j]));
        for (int i = 1; i < 4; ++i)
          s = _mm256_add_pd(s, _mm256_mul_pd(q[i], _mm256_set1_pd(kMsmInverse[i][j])));
        mh[j] = s;
      }
    }
    z[hh] = _mm256_cvtps_pd(_mm_loadu_ps(depth[h] + 4 * half));
  }
  msm_intensity4n<2 * N>(m, z, k.alpha, k.hausdorff, g);
  for (int hh = 0; hh < 2 * N; ++hh)
    _mm_storeu_ps(out[hh / 2] + 4 * (hh % 2), _mm256_cvtpd_ps(_mm256_sub_pd(one, g[hh])));
}

// The AVX-512 table takes these too (techniques/lookup/lookup_batches_avx512.cpp).
template void msm_mixed<1>(const MsmLookupConsts&, const double (*const*)[8], const float* const*,
                           float* const*);
template void msm_mixed<2>(const MsmLookupConsts&, const double (*const*)[8], const float* const*,
                           float* const*);

// msm_intensity4n on G groups of 4 lanes (m[i][4h + lane]).
template <int G>
void msm_intensity_lanes(const double (*m)[32], const double* z, double alpha, bool hausdorff,
                         double* out) {
  __m256d mv[G][4], zv[G], g[G];
  for (int h = 0; h < G; ++h) {
    for (int i = 0; i < 4; ++i) mv[h][i] = _mm256_loadu_pd(m[i] + 4 * h);
    zv[h] = _mm256_loadu_pd(z + 4 * h);
  }
  msm_intensity4n<G>(mv, zv, alpha, hausdorff, g);
  for (int h = 0; h < G; ++h) _mm256_storeu_pd(out + 4 * h, g[h]);
}

// Rotated Poisson PCF: poisson_visibility (depth_compare.cpp; no rpdb) for the 8 lanes of a
// batch, its float operations in its order: the tap's coordinates, bilinear_taps (floor_int,
// clamp to the face), the four compares as gathers from the stored distances, the weighted sum,
// the mean.
inline __m256i clamp_to(__m256i v, __m256i hi) {
  return _mm256_min_epi32(_mm256_max_epi32(v, _mm256_setzero_si256()), hi);
}
// 1 where depth <= the stored distance of texel (x, y) of the lane's face, else 0.
inline __m256 lit_at(const MapLookupConsts& c, __m256i offset, __m256i width,
                     __m256 gather_mask, __m256 depth, __m256i x, __m256i y) {
  const __m256 d = stored_distance(c, offset, width, x, y, gather_mask);
  return _mm256_and_ps(_mm256_cmp_ps(depth, d, _CMP_LE_OQ), _mm256_set1_ps(1.0f));
}

void poisson_batch(const MapLookupConsts& c, const Receivers8& r, const float* cosv,
                   const float* sinv, const vec2* points, int n, float radius, float* out) {
  const __m256 one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
  const __m256i zero_i = _mm256_setzero_si256(), one_i = _mm256_set1_epi32(1);
  const __m256 sx = _mm256_load_ps(r.sx), sy = _mm256_load_ps(r.sy);
  const __m256 depth = _mm256_load_ps(r.depth);
  const __m256i active = _mm256_load_si256(reinterpret_cast<const __m256i*>(r.active));
  const __m256 gather_mask = _mm256_castsi256_ps(  // active lanes are all ones, others 0
      _mm256_xor_si256(_mm256_cmpeq_epi32(active, zero_i), _mm256_set1_epi32(-1)));
  // Inactive lanes read face 0's first texel (masked gathers skip them anyway).
  const __m256i face = _mm256_and_si256(
      _mm256_load_si256(reinterpret_cast<const __m256i*>(r.face)), _mm256_castps_si256(gather_mask));
  const __m256i width = face_lanes(c.width, face), height = face_lanes(c.height, face);
  const __m256i offset = face_lanes(c.offset, face);
  const __m256i wmax = _mm256_sub_epi32(width, one_i), hmax = _mm256_sub_epi32(height, one_i);
  const __m256 cs = _mm256_loadu_ps(cosv), sn = _mm256_loadu_ps(sinv);
  const __m256 rad = _mm256_set1_ps(radius);
  __m256 lit = _mm256_setzero_ps();
  for (int p = 0; p < n; ++p) {
    __m256 tx, ty;
    rotated_tap(sx, sy, rad, cs, sn, points[p].x, points[p].y, tx, ty);
    const __m256 gx = _mm256_sub_ps(tx, half), gy = _mm256_sub_ps(ty, half);
    const __m256i ix = floor_lanes(gx), iy = floor_lanes(gy);
    const __m256 fx = _mm256_sub_ps(gx, _mm256_cvtepi32_ps(ix));
    const __m256 fy = _mm256_sub_ps(gy, _mm256_cvtepi32_ps(iy));
    const __m256i x0 = clamp_to(ix, wmax), x1 = clamp_to(_mm256_add_epi32(ix, one_i), wmax);
    const __m256i y0 = clamp_to(iy, hmax), y1 = clamp_to(_mm256_add_epi32(iy, one_i), hmax);
    const __m256 ofx = _mm256_sub_ps(one, fx), ofy = _mm256_sub_ps(one, fy);
    const __m256 a00 = lit_at(c, offset, width, gather_mask, depth, x0, y0);
    const __m256 a10 = lit_at(c, offset, width, gather_mask, depth, x1, y0);
    const __m256 a01 = lit_at(c, offset, width, gather_mask, depth, x0, y1);
    const __m256 a11 = lit_at(c, offset, width, gather_mask, depth, x1, y1);
    const __m256 top = _mm256_add_ps(_mm256_mul_ps(ofx, a00), _mm256_mul_ps(fx, a10));
    const __m256 bot = _mm256_add_ps(_mm256_mul_ps(ofx, a01), _mm256_mul_ps(fx, a11));
    lit = _mm256_add_ps(lit, _mm256_add_ps(_mm256_mul_ps(ofy, top), _mm256_mul_ps(fy, bot)));
  }
  _mm256_storeu_ps(out, _mm256_div_ps(lit, _mm256_set1_ps(float(n))));
}

// PCSS (pcss.cpp's pcss_visibility, stages 1 and 4): lanes whose tap (x, y) lies outside
// [1, w − 1] × [1, h − 1], where tap_face would look it up in another face.
inline __m256 pcss_outside(__m256 x, __m256 y, __m256 wm1, __m256 hm1) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 in = _mm256_and_ps(
      _mm256_and_ps(_mm256_cmp_ps(x, one, _CMP_GE_OQ), _mm256_cmp_ps(y, one, _CMP_GE_OQ)),
      _mm256_and_ps(_mm256_cmp_ps(x, wm1, _CMP_LE_OQ), _mm256_cmp_ps(y, hm1, _CMP_LE_OQ)));
  return _mm256_xor_ps(in, _mm256_castsi256_ps(_mm256_set1_epi32(-1)));
}

// The lanes' faces (inactive lanes read face 0) and their image bounds.
struct PcssFaces {
  __m256i width, offset;
  __m256 wm1, hm1;
};
inline PcssFaces pcss_faces(const MapLookupConsts& mc, const Receivers8& r, __m256 live) {
  const __m256i face = _mm256_and_si256(_mm256_load_si256(reinterpret_cast<const __m256i*>(r.face)),
                                        _mm256_castps_si256(live));
  PcssFaces f;
  f.width = face_lanes(mc.width, face);
  const __m256i height = face_lanes(mc.height, face);
  f.offset = face_lanes(mc.offset, face);
  f.wm1 = _mm256_sub_ps(_mm256_cvtepi32_ps(f.width), _mm256_set1_ps(1.0f));
  f.hm1 = _mm256_sub_ps(_mm256_cvtepi32_ps(height), _mm256_set1_ps(1.0f));
  return f;
}
inline __m256 lanes_of(const int32_t* flags) {
  const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(flags));
  return _mm256_castsi256_ps(
      _mm256_xor_si256(_mm256_cmpeq_epi32(v, _mm256_setzero_si256()), _mm256_set1_epi32(-1)));
}

// 1. Blocker search: the nearest texel of each tap (inside the image st >= 1, so truncation is
// clamp_texel's floor), a blocker where it is nearer than the receiver plane's depth there.
void pcss_search(const MapLookupConsts& mc, const Receivers8& r, const float* rs, const float* cs,
                 const float* sn, const float* gxv, const float* gyv, const int32_t* active,
                 const vec2* points, int n, double* sums, int32_t* counts, float* outside_out) {
  const __m256 live = lanes_of(active);
  const PcssFaces f = pcss_faces(mc, r, live);
  const __m256 sx = _mm256_load_ps(r.sx), sy = _mm256_load_ps(r.sy);
  const __m256 depth = _mm256_load_ps(r.depth);
  const __m256 gx = _mm256_loadu_ps(gxv), gy = _mm256_loadu_ps(gyv);
  __m256 outside = _mm256_setzero_ps();
  __m256d sum_lo = _mm256_setzero_pd(), sum_hi = _mm256_setzero_pd();
  __m256i count = _mm256_setzero_si256();
  const __m256 rad = _mm256_loadu_ps(rs), c0 = _mm256_loadu_ps(cs), s0 = _mm256_loadu_ps(sn);
  for (int p = 0; p < n; ++p) {
    __m256 tx, ty;
    rotated_tap(sx, sy, rad, c0, s0, points[p].x, points[p].y, tx, ty);
    outside = _mm256_or_ps(outside, pcss_outside(tx, ty, f.wm1, f.hm1));
    const __m256 ok = _mm256_andnot_ps(outside, live);
    const __m256i ix = _mm256_cvttps_epi32(tx), iy = _mm256_cvttps_epi32(ty);
    const __m256 z = stored_distance(mc, f.offset, f.width, ix, iy, ok);
    const __m256 thr = _mm256_add_ps(depth, _mm256_add_ps(_mm256_mul_ps(gx, _mm256_sub_ps(tx, sx)),
                                                          _mm256_mul_ps(gy, _mm256_sub_ps(ty, sy))));
    const __m256 blocker = _mm256_and_ps(_mm256_cmp_ps(z, thr, _CMP_LT_OQ), ok);
    const __m256 zb = _mm256_and_ps(z, blocker);  // +0 where not a blocker
    sum_lo = _mm256_add_pd(sum_lo, _mm256_cvtps_pd(_mm256_castps256_ps128(zb)));
    sum_hi = _mm256_add_pd(sum_hi, _mm256_cvtps_pd(_mm256_extractf128_ps(zb, 1)));
    count = _mm256_sub_epi32(count, _mm256_castps_si256(blocker));
  }
  _mm256_storeu_pd(sums, sum_lo);
  _mm256_storeu_pd(sums + 4, sum_hi);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(counts), count);
  _mm256_storeu_ps(outside_out, outside);
}

// 4. Rotated Poisson PCF over each lane's radius: bilinear_taps inside the image (floor is
// truncation, no clamping), each tap compared with the receiver plane's depth at its texel.
void pcss_pcf(const MapLookupConsts& mc, const Receivers8& r, const float* radius,
              const float* cs, const float* sn, const float* gxv, const float* gyv,
              const int32_t* active, const int32_t* live_lanes, const vec2* points, int n,
              float* vis, float* outside_out) {
  const PcssFaces f = pcss_faces(mc, r, lanes_of(active));
  const __m256 live = lanes_of(live_lanes);
  const __m256 sx = _mm256_load_ps(r.sx), sy = _mm256_load_ps(r.sy);
  const __m256 depth = _mm256_load_ps(r.depth);
  const __m256 gx = _mm256_loadu_ps(gxv), gy = _mm256_loadu_ps(gyv);
  const __m256 rad = _mm256_loadu_ps(radius), c1 = _mm256_loadu_ps(cs), s1 = _mm256_loadu_ps(sn);
  const __m256 one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
  const __m256i one_i = _mm256_set1_epi32(1);
  __m256 outside = _mm256_setzero_ps();
  __m256 lit = _mm256_setzero_ps();
  for (int p = 0; p < n; ++p) {
    __m256 tx, ty;
    rotated_tap(sx, sy, rad, c1, s1, points[p].x, points[p].y, tx, ty);
    outside = _mm256_or_ps(outside, pcss_outside(tx, ty, f.wm1, f.hm1));
    const __m256 ok = _mm256_andnot_ps(outside, live);
    const __m256 bx = _mm256_sub_ps(tx, half), by = _mm256_sub_ps(ty, half);
    const __m256i x0 = _mm256_cvttps_epi32(bx), y0 = _mm256_cvttps_epi32(by);
    const __m256 fx = _mm256_sub_ps(bx, _mm256_cvtepi32_ps(x0));
    const __m256 fy = _mm256_sub_ps(by, _mm256_cvtepi32_ps(y0));
    const __m256i x1 = _mm256_add_epi32(x0, one_i), y1 = _mm256_add_epi32(y0, one_i);
    __m256 a[4];
    const __m256i xs[4] = {x0, x1, x0, x1}, ys[4] = {y0, y0, y1, y1};
    for (int i = 0; i < 4; ++i) {
      const __m256 d = stored_distance(mc, f.offset, f.width, xs[i], ys[i], ok);
      const __m256 cx = _mm256_add_ps(_mm256_cvtepi32_ps(xs[i]), half);
      const __m256 cy = _mm256_add_ps(_mm256_cvtepi32_ps(ys[i]), half);
      const __m256 dt = _mm256_add_ps(depth, _mm256_add_ps(_mm256_mul_ps(gx, _mm256_sub_ps(cx, sx)),
                                                           _mm256_mul_ps(gy, _mm256_sub_ps(cy, sy))));
      a[i] = _mm256_and_ps(_mm256_cmp_ps(dt, d, _CMP_LE_OQ), one);
    }
    const __m256 ofx = _mm256_sub_ps(one, fx), ofy = _mm256_sub_ps(one, fy);
    const __m256 top = _mm256_add_ps(_mm256_mul_ps(ofx, a[0]), _mm256_mul_ps(fx, a[1]));
    const __m256 bot = _mm256_add_ps(_mm256_mul_ps(ofx, a[2]), _mm256_mul_ps(fx, a[3]));
    lit = _mm256_add_ps(lit, _mm256_add_ps(_mm256_mul_ps(ofy, top), _mm256_mul_ps(fy, bot)));
  }
  _mm256_storeu_ps(vis, _mm256_div_ps(lit, _mm256_set1_ps(float(n))));
  _mm256_storeu_ps(outside_out, outside);
}

}  // namespace shadowlab::lookup_batches_avx2

namespace shadowlab {
extern constinit const LookupBatchKernels kLookupBatchesAvx2{
    Isa::avx2,
    lookup_batches_avx2::esm_combine8,
    lookup_batches_avx2::vsm_batch,
    lookup_batches_avx2::evsm_batch,
    lookup_batches_avx2::msm_mixed<1>,
    lookup_batches_avx2::msm_mixed<2>,
    nullptr,
    nullptr,
    lookup_batches_avx2::msm_intensity_lanes<1>,
    lookup_batches_avx2::msm_intensity_lanes<2>,
    4,
    8,
    lookup_batches_avx2::poisson_batch,
    lookup_batches_avx2::pcss_search,
    lookup_batches_avx2::pcss_pcf};
}  // namespace shadowlab
#endif
