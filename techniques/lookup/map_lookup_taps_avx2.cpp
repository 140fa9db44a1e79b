// The AVX2 taps of the lookup (techniques/lookup/map_lookup_simd.h): the bilinear footprints of 8
// receivers in planes of one, two or four values per texel, MSM's bilinear mix, and the
// prefetch of the next batch's rows. Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include "techniques/lookup/map_lookup_lanes_avx2.h"

namespace shadowlab::lookup_avx2 {

#include "techniques/filters/moments_common/chebyshev_avx2.inl"

void bilinear8(const MapLookupConsts& c, const Receivers8& r,
               const PlaneGather* planes, int n, float (*values)[4][8], float* fx,
               float* fy) {
  const __m256i face = _mm256_load_si256(reinterpret_cast<const __m256i*>(r.face));
  const __m256 active = _mm256_castsi256_ps(_mm256_load_si256(reinterpret_cast<const __m256i*>(r.active)));
  const __m256 gx = _mm256_sub_ps(_mm256_load_ps(r.sx), set(0.5f));
  const __m256 gy = _mm256_sub_ps(_mm256_load_ps(r.sy), set(0.5f));
  const __m256i ix = floor_i(gx), iy = floor_i(gy);
  _mm256_storeu_ps(fx, _mm256_sub_ps(gx, _mm256_cvtepi32_ps(ix)));
  _mm256_storeu_ps(fy, _mm256_sub_ps(gy, _mm256_cvtepi32_ps(iy)));
  const __m256i w = lane_i(c.width, face), h = lane_i(c.height, face);
  const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
  const __m256i wm = _mm256_sub_epi32(w, one), hm = _mm256_sub_epi32(h, one);
  const __m256i x0 = clamp_i(ix, zero, wm), x1 = clamp_i(_mm256_add_epi32(ix, one), zero, wm);
  const __m256i r0 = _mm256_mullo_epi32(clamp_i(iy, zero, hm), w);
  const __m256i r1 = _mm256_mullo_epi32(clamp_i(_mm256_add_epi32(iy, one), zero, hm), w);
  const __m256i idx[4] = {_mm256_add_epi32(r0, x0), _mm256_add_epi32(r0, x1),
                          _mm256_add_epi32(r1, x0), _mm256_add_epi32(r1, x1)};
  for (int p = 0; p < n; ++p) {
    const __m256i off = lane_i(planes[p].offset, face);
    for (int t = 0; t < 4; ++t)
      _mm256_storeu_ps(values[p][t], _mm256_mask_i32gather_ps(_mm256_setzero_ps(), planes[p].base,
                                                              _mm256_add_epi32(off, idx[t]), active, 4));
  }
}

// bilinear8 with plain loads instead of gathers: each lane's two taps of a row, (x0, y)
// and (x0 + 1, y), are adjacent floats, so one 8-byte load fetches both (half the element
// loads of the gathers, and no gather microcode, which costs most of the filters' lookups on
// the AMD parts we measure on: docs/performance.md). The pair starts at
// clamp(ix, 0, w − 2), inside the row; a lane clamped at the left edge takes the pair's first
// value for both taps, one at the right edge its second, so the taps are bilinear_taps' clamped
// texels as before, bit for bit. Inactive lanes load texel 0 of face 0's plane and are zeroed,
// as the masked gathers leave them. Needs every face at least 2 texels wide (the dispatcher
// below checks).
void bilinear8_pairs(const MapLookupConsts& c, const Receivers8& r,
                     const PlaneGather* planes, int n, float (*values)[4][8],
                     float* fx, float* fy) {
  const __m256i face = _mm256_load_si256(reinterpret_cast<const __m256i*>(r.face));
  const __m256 active = _mm256_castsi256_ps(_mm256_load_si256(reinterpret_cast<const __m256i*>(r.active)));
  const __m256i w = lane_i(c.width, face), h = lane_i(c.height, face);
  const int active_bits = _mm256_movemask_ps(active);
  const __m256i one = _mm256_set1_epi32(1), zero = _mm256_setzero_si256();
  const __m256i wm = _mm256_sub_epi32(w, one), hm = _mm256_sub_epi32(h, one);
  if (_mm256_movemask_ps(_mm256_and_ps(active, _mm256_castsi256_ps(_mm256_cmpgt_epi32(one, wm)))) ||
      active_bits == 0) {
    // A face 1 texel wide (no pair fits), or nothing to load: the gathers.
    bilinear8(c, r, planes, n, values, fx, fy);
    return;
  }
  const __m256 gx = _mm256_sub_ps(_mm256_load_ps(r.sx), set(0.5f));
  const __m256 gy = _mm256_sub_ps(_mm256_load_ps(r.sy), set(0.5f));
  const __m256i ix = floor_i(gx), iy = floor_i(gy);
  _mm256_storeu_ps(fx, _mm256_sub_ps(gx, _mm256_cvtepi32_ps(ix)));
  _mm256_storeu_ps(fy, _mm256_sub_ps(gy, _mm256_cvtepi32_ps(iy)));
  const __m256i wm2 = _mm256_sub_epi32(wm, one);
  const __m256i start = clamp_i(ix, zero, wm2);
  // Lanes clamped at the left edge (both taps = texel 0) and at the right edge (both = w − 1).
  const __m256 left = _mm256_castsi256_ps(_mm256_cmpgt_epi32(zero, ix));
  const __m256 right = _mm256_castsi256_ps(_mm256_cmpgt_epi32(ix, wm2));
  const __m256i row[2] = {
      _mm256_add_epi32(_mm256_mullo_epi32(clamp_i(iy, zero, hm), w), start),
      _mm256_add_epi32(_mm256_mullo_epi32(clamp_i(_mm256_add_epi32(iy, one), zero, hm), w), start)};
  const __m256i order = _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7);
  const int first_active = __builtin_ctz(unsigned(active_bits));
  for (int p = 0; p < n; ++p) {
    const __m256i off = lane_i(planes[p].offset, face);
    for (int y = 0; y < 2; ++y) {
      alignas(32) int32_t at[8];
      _mm256_store_si256(reinterpret_cast<__m256i*>(at), _mm256_add_epi32(off, row[y]));
      // Inactive lanes (their face may not even be rendered) load an active lane's pair.
      for (int k = 0; k < 8; ++k)
        if (!((active_bits >> k) & 1)) at[k] = at[first_active];
      // movq loads (the pair is only 4-byte aligned: _mm_loadl_epi64 reads through an
      // unaligned type, a double load would not be allowed to).
      auto pair = [&](int k) {
        return _mm_loadl_epi64(reinterpret_cast<const __m128i*>(planes[p].base + at[k]));
      };
      const __m128i q0 = _mm_unpacklo_epi64(pair(0), pair(1));
      const __m128i q1 = _mm_unpacklo_epi64(pair(2), pair(3));
      const __m128i q2 = _mm_unpacklo_epi64(pair(4), pair(5));
      const __m128i q3 = _mm_unpacklo_epi64(pair(6), pair(7));
      // A = (a0 b0 a1 b1 | a2 b2 a3 b3), B likewise for lanes 4–7 (a: first tap, b: second).
      const __m256 A = _mm256_castsi256_ps(_mm256_set_m128i(q1, q0));
      const __m256 B = _mm256_castsi256_ps(_mm256_set_m128i(q3, q2));
      const __m256 first = _mm256_permutevar8x32_ps(_mm256_shuffle_ps(A, B, 0x88), order);
      const __m256 second = _mm256_permutevar8x32_ps(_mm256_shuffle_ps(A, B, 0xDD), order);
      _mm256_storeu_ps(values[p][2 * y], _mm256_and_ps(_mm256_blendv_ps(first, second, right), active));
      _mm256_storeu_ps(values[p][2 * y + 1],
                       _mm256_and_ps(_mm256_blendv_ps(second, first, left), active));
    }
  }
}

// v with each inactive lane's value replaced by the first active lane's (active: all-ones lanes;
// active_bits: its movemask, not 0), so that every lane holds a valid index without a branch per
// lane.
inline __m256i fill_inactive(__m256i v, __m256i active, int active_bits) {
  const __m256i first = _mm256_set1_epi32(__builtin_ctz(unsigned(active_bits)));
  return _mm256_blendv_epi8(_mm256_permutevar8x32_epi32(v, first), v, active);
}

// The shared front of the interleaved kernels below, for a plane of n values per texel (texel
// i's at plane.base[offset + n·i + v]): the fractions into fx, fy, and per lane and tap row the
// float index where its pair of texels starts, at clamp(ix, 0, w − 2), inactive lanes pointed at
// an active lane's pair; lanes clamped at the left edge take the first texel for both taps, at
// the right edge the second (bilinear_taps' clamped texels). With a face 1 texel wide, or no
// active lane, it fills values lane by lane itself and returns false.
struct PairRows {
  __m256 active, left, right;
  alignas(32) int32_t at[2][8];
};
inline bool pair_rows(const MapLookupConsts& c, const Receivers8& r, const PlaneGather& plane,
                      int n, float (*values)[4][8], float* fx, float* fy, PairRows& out) {
  const __m256i face = _mm256_load_si256(reinterpret_cast<const __m256i*>(r.face));
  out.active = _mm256_castsi256_ps(_mm256_load_si256(reinterpret_cast<const __m256i*>(r.active)));
  const __m256i w = lane_i(c.width, face), h = lane_i(c.height, face);
  const int active_bits = _mm256_movemask_ps(out.active);
  const __m256i one = _mm256_set1_epi32(1), zero = _mm256_setzero_si256(), nv = _mm256_set1_epi32(n);
  const __m256i wm = _mm256_sub_epi32(w, one), hm = _mm256_sub_epi32(h, one);
  const __m256 gx = _mm256_sub_ps(_mm256_load_ps(r.sx), set(0.5f));
  const __m256 gy = _mm256_sub_ps(_mm256_load_ps(r.sy), set(0.5f));
  const __m256i ix = floor_i(gx), iy = floor_i(gy);
  _mm256_storeu_ps(fx, _mm256_sub_ps(gx, _mm256_cvtepi32_ps(ix)));
  _mm256_storeu_ps(fy, _mm256_sub_ps(gy, _mm256_cvtepi32_ps(iy)));
  const __m256i off = lane_i(plane.offset, face);
  const __m256i r0 = _mm256_mullo_epi32(clamp_i(iy, zero, hm), w);
  const __m256i r1 = _mm256_mullo_epi32(clamp_i(_mm256_add_epi32(iy, one), zero, hm), w);
  if (_mm256_movemask_ps(_mm256_and_ps(out.active, _mm256_castsi256_ps(_mm256_cmpgt_epi32(one, wm)))) ||
      active_bits == 0) {
    const __m256i x0 = clamp_i(ix, zero, wm), x1 = clamp_i(_mm256_add_epi32(ix, one), zero, wm);
    alignas(32) int32_t at[4][8];
    const __m256i idx[4] = {_mm256_add_epi32(r0, x0), _mm256_add_epi32(r0, x1),
                            _mm256_add_epi32(r1, x0), _mm256_add_epi32(r1, x1)};
    for (int t = 0; t < 4; ++t)
      _mm256_store_si256(reinterpret_cast<__m256i*>(at[t]),
                         _mm256_add_epi32(off, _mm256_mullo_epi32(idx[t], nv)));
    for (int t = 0; t < 4; ++t)
      for (int k = 0; k < 8; ++k) {
        const bool on = (active_bits >> k) & 1;
        for (int v = 0; v < n; ++v) values[v][t][k] = on ? plane.base[at[t][k] + v] : 0.0f;
      }
    return false;
  }
  const __m256i wm2 = _mm256_sub_epi32(wm, one);
  const __m256i start = clamp_i(ix, zero, wm2);
  out.left = _mm256_castsi256_ps(_mm256_cmpgt_epi32(zero, ix));
  out.right = _mm256_castsi256_ps(_mm256_cmpgt_epi32(ix, wm2));
  // Inactive lanes take the first active lane's index (fill_inactive), where a branch per lane
  // was a third of this function's instructions.
  const __m256i row[2] = {_mm256_add_epi32(r0, start), _mm256_add_epi32(r1, start)};
  for (int y = 0; y < 2; ++y)
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.at[y]),
                       fill_inactive(_mm256_add_epi32(off, _mm256_mullo_epi32(row[y], nv)),
                                     _mm256_castps_si256(out.active), active_bits));
  return true;
}

// Tap row y's first and second texel values from their transposed lanes, with the edge rule.
inline void store_pair(const PairRows& p, __m256 first, __m256 second, float (*tap)[8], int y) {
  _mm256_storeu_ps(tap[2 * y], _mm256_and_ps(_mm256_blendv_ps(first, second, p.right), p.active));
  _mm256_storeu_ps(tap[2 * y + 1], _mm256_and_ps(_mm256_blendv_ps(second, first, p.left), p.active));
}

// The bilinear footprint of 8 receivers in one interleaved plane of two values per texel
// (variance_map.cpp's mean and variance, EVSM2's): one 16-byte load per lane and tap row fetches
// both taps' two values, then a 4 × 4 transpose in each half. values[v][tap][lane].
void bilinear8_interleaved2(const MapLookupConsts& c, const Receivers8& r,
                            const PlaneGather& plane, float (*values)[4][8],
                            float* fx, float* fy) {
  PairRows p;
  if (!pair_rows(c, r, plane, 2, values, fx, fy, p)) return;
  for (int y = 0; y < 2; ++y) {
    // Lane k's (u0 v0 u1 v1): the first tap's two values, then the second's.
    auto quad = [&](int k) { return _mm_loadu_ps(plane.base + p.at[y][k]); };
    // Y_k = lanes k (low half) and k + 4 (high half); a 4 × 4 transpose in each half.
    const __m256 y0 = _mm256_set_m128(quad(4), quad(0)), y1 = _mm256_set_m128(quad(5), quad(1));
    const __m256 y2 = _mm256_set_m128(quad(6), quad(2)), y3 = _mm256_set_m128(quad(7), quad(3));
    const __m256 t0 = _mm256_unpacklo_ps(y0, y1);  // u0 of lanes 0 1, v0 of lanes 0 1
    const __m256 t1 = _mm256_unpackhi_ps(y0, y1);  // u1 …, v1 …
    const __m256 t2 = _mm256_unpacklo_ps(y2, y3);  // lanes 2 3
    const __m256 t3 = _mm256_unpackhi_ps(y2, y3);
    store_pair(p, _mm256_shuffle_ps(t0, t2, 0x44), _mm256_shuffle_ps(t1, t3, 0x44), values[0], y);
    store_pair(p, _mm256_shuffle_ps(t0, t2, 0xEE), _mm256_shuffle_ps(t1, t3, 0xEE), values[1], y);
  }
}

// The same for four values per texel (moment_shadow_map.cpp's moments, EVSM4's two warps): one
// 32-byte load per lane and tap row fetches both taps' four values, then an 8 × 8 transpose.
void bilinear8_interleaved4(const MapLookupConsts& c, const Receivers8& r,
                            const PlaneGather& plane, float (*values)[4][8],
                            float* fx, float* fy) {
  PairRows p;
  if (!pair_rows(c, r, plane, 4, values, fx, fy, p)) return;
  for (int y = 0; y < 2; ++y) {
    // R_k = lane k's 8 floats: the first tap's values 0..3, then the second tap's.
    __m256 R[8];
    for (int k = 0; k < 8; ++k) R[k] = _mm256_loadu_ps(plane.base + p.at[y][k]);
    // 8 × 8 transpose: O[j][k] = R[k][j].
    __m256 t[8], tt[8], O[8];
    for (int q = 0; q < 4; ++q) {
      t[2 * q] = _mm256_unpacklo_ps(R[2 * q], R[2 * q + 1]);
      t[2 * q + 1] = _mm256_unpackhi_ps(R[2 * q], R[2 * q + 1]);
    }
    for (int q = 0; q < 2; ++q) {
      tt[4 * q + 0] = _mm256_shuffle_ps(t[4 * q], t[4 * q + 2], 0x44);
      tt[4 * q + 1] = _mm256_shuffle_ps(t[4 * q], t[4 * q + 2], 0xEE);
      tt[4 * q + 2] = _mm256_shuffle_ps(t[4 * q + 1], t[4 * q + 3], 0x44);
      tt[4 * q + 3] = _mm256_shuffle_ps(t[4 * q + 1], t[4 * q + 3], 0xEE);
    }
    for (int j = 0; j < 4; ++j) {
      O[j] = _mm256_permute2f128_ps(tt[j], tt[4 + j], 0x20);
      O[4 + j] = _mm256_permute2f128_ps(tt[j], tt[4 + j], 0x31);
    }
    for (int v = 0; v < 4; ++v) store_pair(p, O[v], O[4 + v], values[v], y);
  }
}

// The bilinear mix of the four values per texel for 8 receivers, in double: lane k's
// m[v][k] = Σ_t w_t · value_t (bilinear_weights' w, summed from 0 over taps 0..3, the scalar
// loops' order). Lane by lane, its four values side by side in one vector: each tap is one
// 16-byte load widened to double, times the lane's weight broadcast, so no transpose of the tap
// rows and no round trip of the 16 tap vectors through memory (bilinear8_interleaved4 and
// the batch's reload); then a 4 × 4 transpose per half. Inactive lanes get zeros.
void bilinear8_mix4(const MapLookupConsts& c, const Receivers8& r,
                    const PlaneGather& plane, double (*m)[8]) {
  if (_mm256_testz_si256(_mm256_load_si256(reinterpret_cast<const __m256i*>(r.active)),
                         _mm256_set1_epi32(-1))) {
    // No active lane (a batch of uncovered or unlit pixels): zeros, without pair_rows'
    // lane-by-lane fill.
    for (int v = 0; v < 4; ++v)
      for (int h = 0; h < 2; ++h) _mm256_store_pd(m[v] + 4 * h, _mm256_setzero_pd());
    return;
  }
  PairRows p;
  alignas(32) float values[4][4][8], fx[8], fy[8];
  alignas(32) double w[4][8];  // w[t][lane]
  const bool pairs = pair_rows(c, r, plane, 4, values, fx, fy, p);
  for (int h = 0; h < 2; ++h) {
    __m256d wh[4];
    bilinear_weights4(_mm256_cvtps_pd(_mm_load_ps(fx + 4 * h)),
                      _mm256_cvtps_pd(_mm_load_ps(fy + 4 * h)), wh);
    for (int t = 0; t < 4; ++t) _mm256_store_pd(w[t] + 4 * h, wh[t]);
  }
  __m256d lane[8];
  if (pairs) {
    // Per tap and lane, the float offset of its 4 values: the pair's first texel at at[y], the
    // second 4 floats on, with store_pair's edge rule (a lane clamped at the right edge takes
    // the second texel for both taps, at the left edge the first).
    alignas(32) int32_t off[4][8];
    const __m256i four = _mm256_set1_epi32(4);
    const __m256i right4 = _mm256_and_si256(_mm256_castps_si256(p.right), four);
    const __m256i not_left4 = _mm256_andnot_si256(_mm256_castps_si256(p.left), four);
    for (int y = 0; y < 2; ++y) {
      const __m256i at = _mm256_load_si256(reinterpret_cast<const __m256i*>(p.at[y]));
      _mm256_store_si256(reinterpret_cast<__m256i*>(off[2 * y]), _mm256_add_epi32(at, right4));
      _mm256_store_si256(reinterpret_cast<__m256i*>(off[2 * y + 1]), _mm256_add_epi32(at, not_left4));
    }
    for (int k = 0; k < 8; ++k) {
      __m256d acc = _mm256_setzero_pd();
      for (int t = 0; t < 4; ++t)
        acc = _mm256_add_pd(acc, _mm256_mul_pd(_mm256_broadcast_sd(&w[t][k]),
                                               _mm256_cvtps_pd(_mm_loadu_ps(plane.base + off[t][k]))));
      lane[k] = acc;
    }
  } else {  // pair_rows filled values lane by lane
    for (int k = 0; k < 8; ++k) {
      __m256d acc = _mm256_setzero_pd();
      for (int t = 0; t < 4; ++t)
        acc = _mm256_add_pd(acc, _mm256_mul_pd(_mm256_broadcast_sd(&w[t][k]),
                                               _mm256_cvtps_pd(_mm_setr_ps(values[0][t][k], values[1][t][k],
                                                                           values[2][t][k], values[3][t][k]))));
      lane[k] = acc;
    }
  }
  // Lanes 4h .. 4h + 3 (value v in element v) to m[v][4h ..]: a 4 × 4 transpose.
  const __m256 active = _mm256_load_ps(reinterpret_cast<const float*>(r.active));
  for (int h = 0; h < 2; ++h) {
    const __m256d* L = lane + 4 * h;
    const __m256d t0 = _mm256_unpacklo_pd(L[0], L[1]), t1 = _mm256_unpackhi_pd(L[0], L[1]);
    const __m256d t2 = _mm256_unpacklo_pd(L[2], L[3]), t3 = _mm256_unpackhi_pd(L[2], L[3]);
    const __m256d on = _mm256_castps_pd(_mm256_castsi256_ps(_mm256_cvtepi32_epi64(
        _mm_castps_si128(h ? _mm256_extractf128_ps(active, 1) : _mm256_castps256_ps128(active)))));
    _mm256_store_pd(m[0] + 4 * h, _mm256_and_pd(on, _mm256_permute2f128_pd(t0, t2, 0x20)));
    _mm256_store_pd(m[1] + 4 * h, _mm256_and_pd(on, _mm256_permute2f128_pd(t1, t3, 0x20)));
    _mm256_store_pd(m[2] + 4 * h, _mm256_and_pd(on, _mm256_permute2f128_pd(t0, t2, 0x31)));
    _mm256_store_pd(m[3] + 4 * h, _mm256_and_pd(on, _mm256_permute2f128_pd(t1, t3, 0x31)));
  }
}

void prefetch8(const MapLookupConsts& c, const Receivers8& r,
               const PlaneGather& plane, int floats_per_texel) {
  const __m256i face = _mm256_load_si256(reinterpret_cast<const __m256i*>(r.face));
  const __m256i active = _mm256_load_si256(reinterpret_cast<const __m256i*>(r.active));
  const int active_bits = _mm256_movemask_ps(_mm256_castsi256_ps(active));
  if (!active_bits) return;
  const __m256i w = lane_i(c.width, face), h = lane_i(c.height, face);
  const __m256i one = _mm256_set1_epi32(1), zero = _mm256_setzero_si256();
  const __m256i ix = floor_i(_mm256_sub_ps(_mm256_load_ps(r.sx), set(0.5f)));
  const __m256i iy = floor_i(_mm256_sub_ps(_mm256_load_ps(r.sy), set(0.5f)));
  const __m256i x0 = clamp_i(ix, zero, _mm256_sub_epi32(w, one));
  const __m256i y0 = clamp_i(iy, zero, _mm256_sub_epi32(h, one));
  const __m256i y1 = clamp_i(_mm256_add_epi32(iy, one), zero, _mm256_sub_epi32(h, one));
  const __m256i off = lane_i(plane.offset, face), fpt = _mm256_set1_epi32(floats_per_texel);
  // Inactive lanes (whose face may not exist) take the first active lane's rows, as pair_rows'
  // do, so every lane prefetches without a branch.
  alignas(32) int32_t at[2][8];
  const __m256i rows[2] = {y0, y1};
  for (int y = 0; y < 2; ++y) {
    const __m256i a = _mm256_add_epi32(off, _mm256_mullo_epi32(_mm256_add_epi32(_mm256_mullo_epi32(rows[y], w), x0), fpt));
    _mm256_store_si256(reinterpret_cast<__m256i*>(at[y]), fill_inactive(a, active, active_bits));
  }
  for (int k = 0; k < 8; ++k) {
    _mm_prefetch(reinterpret_cast<const char*>(plane.base + at[0][k]), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(plane.base + at[1][k]), _MM_HINT_T0);
  }
}

}  // namespace shadowlab::lookup_avx2
#endif
