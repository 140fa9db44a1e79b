// The AVX-512 path of raster/gbuffer_resolve_simd.h (16 pixels, each its own triangle).
// Compiled with -mavx512f -mavx512vl -mavx512dq -mavx512bw (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "core/gbuffer.h"
#include "raster/gbuffer_resolve_simd.h"

namespace shadowlab::gbuffer_resolve_avx512 {

struct W3 {
  __m512 x, y, z;
};
[[gnu::always_inline]] inline __m512 bw(float v) { return _mm512_set1_ps(v); }
[[gnu::always_inline]] inline W3 load3w(const float (*v)[16]) {
  return {_mm512_load_ps(v[0]), _mm512_load_ps(v[1]), _mm512_load_ps(v[2])};
}
[[gnu::always_inline]] inline __m512 dotw(const W3& a, const W3& b) {
  return _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(a.x, b.x), _mm512_mul_ps(a.y, b.y)),
                       _mm512_mul_ps(a.z, b.z));
}
[[gnu::always_inline]] inline W3 crossw(const W3& a, const W3& b) {
  return {_mm512_sub_ps(_mm512_mul_ps(a.y, b.z), _mm512_mul_ps(b.y, a.z)),
          _mm512_sub_ps(_mm512_mul_ps(a.z, b.x), _mm512_mul_ps(b.z, a.x)),
          _mm512_sub_ps(_mm512_mul_ps(a.x, b.y), _mm512_mul_ps(b.x, a.y))};
}
[[gnu::always_inline]] inline void store3w(vec3* out, const W3& v) {
  alignas(64) float t[3][16];
  _mm512_store_ps(t[0], v.x);
  _mm512_store_ps(t[1], v.y);
  _mm512_store_ps(t[2], v.z);
  float* o = &out[0].x;  // packed vec3s (no glm function in this file)
  for (int i = 0; i < 16; ++i) {
    o[3 * i] = t[0][i];
    o[3 * i + 1] = t[1][i];
    o[3 * i + 2] = t[2][i];
  }
}
[[gnu::always_inline]] inline __m512 absw(__m512 v) {
  return _mm512_andnot_ps(_mm512_set1_ps(-0.0f), v);
}

// resolve8's operations on 16 lanes (compare masks where it blends).
void lanes16(const ResolveRun8& r, const ResolveLanes16& t, int x, int y, const float* inv_w,
             vec3* position, vec3* geo_normal, float* depth_out, uint32_t* mesh_id,
             uint32_t* prim_id, uint8_t* covered) {
  const __m512 zero = _mm512_setzero_ps(), one = bw(1.0f);
  const __m512 xs = _mm512_maskz_cvtepi32_ps(
      0xFFFF, _mm512_add_epi32(_mm512_set1_epi32(x), _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9,
                                                                       10, 11, 12, 13, 14, 15)));
  const __m512 nx = _mm512_sub_ps(
      _mm512_mul_ps(_mm512_div_ps(_mm512_add_ps(xs, bw(0.5f)), bw(float(r.width))), bw(2.0f)), one);
  const float nys = (1.0f - (float(y) + 0.5f) / float(r.height) * 2.0f) * r.sy;
  const __m512 nxs = _mm512_mul_ps(nx, bw(r.sx));
  const W3 d = {_mm512_add_ps(_mm512_add_ps(bw(r.forward.x), _mm512_mul_ps(nxs, bw(r.right.x))),
                              bw(nys * r.up.x)),
                _mm512_add_ps(_mm512_add_ps(bw(r.forward.y), _mm512_mul_ps(nxs, bw(r.right.y))),
                              bw(nys * r.up.y)),
                _mm512_add_ps(_mm512_add_ps(bw(r.forward.z), _mm512_mul_ps(nxs, bw(r.right.z))),
                              bw(nys * r.up.z))};
  const W3 pv = crossw(d, load3w(t.e2));
  const __m512 det = dotw(load3w(t.e1), pv);
  __m512 depth = _mm512_div_ps(one, _mm512_loadu_ps(inv_w));
  const __mmask16 ok_det = _mm512_cmp_ps_mask(absw(det), bw(1e-30f), _CMP_GT_OQ);
  const __m512 inv_det = _mm512_div_ps(one, det);
  const __m512 tt = _mm512_mul_ps(_mm512_load_ps(t.e2q), inv_det);
  const __mmask16 hit =
      __mmask16(ok_det & _mm512_cmp_ps_mask(absw(tt), bw(__builtin_inff()), _CMP_LT_OQ) &
                _mm512_cmp_ps_mask(tt, zero, _CMP_GT_OQ));
  depth = _mm512_mask_blend_ps(hit, depth, tt);
  const W3 pos = {_mm512_add_ps(bw(r.eye.x), _mm512_mul_ps(depth, d.x)),
                  _mm512_add_ps(bw(r.eye.y), _mm512_mul_ps(depth, d.y)),
                  _mm512_add_ps(bw(r.eye.z), _mm512_mul_ps(depth, d.z))};
  W3 gn = load3w(t.gn);
  const W3 to_eye = {_mm512_sub_ps(bw(r.eye.x), pos.x), _mm512_sub_ps(bw(r.eye.y), pos.y),
                     _mm512_sub_ps(bw(r.eye.z), pos.z)};
  const __m512 sign = bw(-0.0f);
  const __mmask16 flip_g = _mm512_cmp_ps_mask(dotw(gn, to_eye), zero, _CMP_LT_OQ);
  gn = {_mm512_mask_xor_ps(gn.x, flip_g, gn.x, sign), _mm512_mask_xor_ps(gn.y, flip_g, gn.y, sign),
        _mm512_mask_xor_ps(gn.z, flip_g, gn.z, sign)};
  // Lanes showing no triangle: the empty values (+0 vectors, +inf depth, no ids).
  const __mmask16 cov = __mmask16(t.covered);
  store3w(position, {_mm512_maskz_mov_ps(cov, pos.x), _mm512_maskz_mov_ps(cov, pos.y),
                     _mm512_maskz_mov_ps(cov, pos.z)});
  store3w(geo_normal, {_mm512_maskz_mov_ps(cov, gn.x), _mm512_maskz_mov_ps(cov, gn.y),
                       _mm512_maskz_mov_ps(cov, gn.z)});
  _mm512_storeu_ps(depth_out, _mm512_mask_blend_ps(cov, bw(__builtin_inff()), depth));
  const __m512i none = _mm512_set1_epi32(-1);
  _mm512_storeu_si512(mesh_id, _mm512_mask_blend_epi32(cov, none, _mm512_load_si512(t.mesh)));
  _mm512_storeu_si512(prim_id, _mm512_mask_blend_epi32(cov, none, _mm512_load_si512(t.prim)));
  _mm_storeu_si128(
      reinterpret_cast<__m128i*>(covered),
      _mm512_maskz_cvtepi32_epi8(0xFFFF, _mm512_maskz_mov_epi32(cov, _mm512_set1_epi32(1))));
}

[[gnu::always_inline]] inline void put3(float (*dst)[16], __mmask16 m, const vec3& v) {
  const float* f = &v.x;  // (no glm function in this file)
  for (int c = 0; c < 3; ++c) _mm512_mask_storeu_ps(dst[c], m, bw(f[c]));
}

uint32_t lanes16_runs(const uint32_t* ids, uint32_t* covered) {
  const __m512i v = _mm512_loadu_si512(ids);
  *covered = _mm512_cmpneq_epi32_mask(v, _mm512_set1_epi32(int(kNoPrimitive)));
  // Lane k against lane k − 1 (lane 0 against lane 15: bit 0 is set below whatever it gives).
  const __m512i prev = _mm512_maskz_alignr_epi32(0xFFFF, v, v, 15);
  return uint32_t(_mm512_cmpneq_epi32_mask(v, prev)) | 1u;
}

void lanes16_fill(ResolveLanes16& l, uint32_t mask, const vec3& e1, const vec3& e2, const vec3& gn,
                  float e2q, uint32_t mesh, uint32_t prim) {
  const __mmask16 m = __mmask16(mask);
  _mm512_mask_storeu_epi32(l.mesh, m, _mm512_set1_epi32(int(mesh)));
  _mm512_mask_storeu_epi32(l.prim, m, _mm512_set1_epi32(int(prim)));
  put3(l.e1, m, e1);
  put3(l.e2, m, e2);
  put3(l.gn, m, gn);
  _mm512_mask_storeu_ps(l.e2q, m, bw(e2q));
}

}  // namespace shadowlab::gbuffer_resolve_avx512
#endif
