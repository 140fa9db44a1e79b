#include "raster/gbuffer_resolve_simd.h"


#if defined(__x86_64__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

#include "core/isa.h"
#include "core/gbuffer.h"
#include "core/simd_target.h"

namespace shadowlab {

#ifdef SHADOWLAB_HAVE_X86
namespace {

#define SL_AVX2 SL_TARGET("avx2")

struct V3 {
  __m256 x, y, z;
};

SL_AVX2 inline __m256 bc(float v) { return _mm256_set1_ps(v); }
SL_AVX2 inline V3 bc3(const vec3& v) { return {bc(v.x), bc(v.y), bc(v.z)}; }
// glm::dot order: (a.x·b.x + a.y·b.y) + a.z·b.z.
SL_AVX2 inline __m256 dot(const V3& a, const V3& b) {
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y)),
                       _mm256_mul_ps(a.z, b.z));
}
// glm::cross: (x.y·y.z − y.y·x.z, x.z·y.x − y.z·x.x, x.x·y.y − y.x·x.y).
SL_AVX2 inline V3 cross(const V3& a, const V3& b) {
  return {_mm256_sub_ps(_mm256_mul_ps(a.y, b.z), _mm256_mul_ps(b.y, a.z)),
          _mm256_sub_ps(_mm256_mul_ps(a.z, b.x), _mm256_mul_ps(b.z, a.x)),
          _mm256_sub_ps(_mm256_mul_ps(a.x, b.y), _mm256_mul_ps(b.x, a.y))};
}
// ((l0·a + l1·b) + l2·c), componentwise: glm's l.x*a + l.y*b + l.z*c.
SL_AVX2 inline __m256 interp(__m256 l0, __m256 l1, __m256 l2, float a, float b, float c) {
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(l0, bc(a)), _mm256_mul_ps(l1, bc(b))),
                       _mm256_mul_ps(l2, bc(c)));
}
SL_AVX2 inline __m256 select(__m256 mask, __m256 if_true, __m256 if_false) {
  return _mm256_blendv_ps(if_false, if_true, mask);
}
SL_AVX2 inline void store3(vec3* out, const V3& v) {
  alignas(32) float t[3][8];
  _mm256_store_ps(t[0], v.x);
  _mm256_store_ps(t[1], v.y);
  _mm256_store_ps(t[2], v.z);
  for (int i = 0; i < 8; ++i) out[i] = vec3(t[0][i], t[1][i], t[2][i]);
}

SL_AVX2 inline V3 load3(const float (*v)[8]) {
  return {_mm256_load_ps(v[0]), _mm256_load_ps(v[1]), _mm256_load_ps(v[2])};
}

// The triangle terms of one triangle for all 8 lanes (broadcasts).
struct SameTriangle {
  const ResolveRun8& r;
  SL_AVX2 V3 e1() const { return bc3(r.e1); }
  SL_AVX2 V3 e2() const { return bc3(r.e2); }
  SL_AVX2 V3 gn() const { return bc3(r.gn); }
  SL_AVX2 __m256 e2q() const { return bc(r.e2q); }
};

SL_AVX2 inline V3 sub3(const V3& a, const V3& b) {
  return {_mm256_sub_ps(a.x, b.x), _mm256_sub_ps(a.y, b.y), _mm256_sub_ps(a.z, b.z)};
}

// Each lane's own triangle: the terms load_triangle (gbuffer_pass.cpp) computes, from the
// lanes' vertices with its operations in its order (glm's -, cross, dot, length and /).
struct LaneTriangles {
  V3 e1_, e2_, gn_;
  __m256 e2q_;
  SL_AVX2 LaneTriangles(const ResolveLanes8& l, const vec3& eye) {
    const V3 p0 = load3(l.v[0]);
    e1_ = sub3(load3(l.v[1]), p0);
    e2_ = sub3(load3(l.v[2]), p0);
    e2q_ = dot(e2_, cross(sub3(bc3(eye), p0), e1_));
    const V3 n = cross(e1_, e2_);
    const __m256 nl = _mm256_sqrt_ps(dot(n, n));
    const __m256 ok = _mm256_cmp_ps(nl, _mm256_setzero_ps(), _CMP_GT_OQ);
    gn_ = {select(ok, _mm256_div_ps(n.x, nl), _mm256_setzero_ps()),
           select(ok, _mm256_div_ps(n.y, nl), bc(1.0f)),
           select(ok, _mm256_div_ps(n.z, nl), _mm256_setzero_ps())};
  }
  SL_AVX2 V3 e1() const { return e1_; }
  SL_AVX2 V3 e2() const { return e2_; }
  SL_AVX2 V3 gn() const { return gn_; }
  SL_AVX2 __m256 e2q() const { return e2q_; }
};

// The scalar resolve's operations for 8 pixels (gbuffer_pass.cpp), triangle terms from `t`.
template <class Terms>
SL_AVX2 inline void resolve8(const ResolveRun8& r, const Terms& t, int x, int y,
                             const float* inv_w, vec3* position, vec3* geo_normal,
                             float* depth_out) {
  const __m256 zero = _mm256_setzero_ps(), one = bc(1.0f), sign = bc(-0.0f);
  // Ray directions, as PixelRays::dir: the columns' forward + (nx·sx)·right from the table
  // (its division per pixel made once per pass), plus the row's (ny·sy)·up.
  const float nys = (1.0f - (float(y) + 0.5f) / float(r.height) * 2.0f) * r.sy;
  const float* col = r.columns + x;
  const size_t w = size_t(r.width);
  const V3 d = {_mm256_add_ps(_mm256_loadu_ps(col), bc(nys * r.up.x)),
                _mm256_add_ps(_mm256_loadu_ps(col + w), bc(nys * r.up.y)),
                _mm256_add_ps(_mm256_loadu_ps(col + 2 * w), bc(nys * r.up.z))};
  // Möller–Trumbore with the triangle's constant terms.
  const V3 pv = cross(d, t.e2());
  const __m256 det = dot(t.e1(), pv);
  const __m256 ok_det = _mm256_cmp_ps(_mm256_andnot_ps(sign, det), bc(1e-30f), _CMP_GT_OQ);
  const __m256 inv_det = _mm256_div_ps(one, det);
  const __m256 tt = _mm256_mul_ps(t.e2q(), inv_det);
  const __m256 finite = _mm256_cmp_ps(_mm256_andnot_ps(sign, tt), bc(__builtin_inff()), _CMP_LT_OQ);
  const __m256 hit = _mm256_and_ps(_mm256_and_ps(ok_det, finite), _mm256_cmp_ps(tt, zero, _CMP_GT_OQ));
  // The raster depth 1 / (1/w) only where the ray missed the plane (almost never: no division
  // when every lane hit).
  const __m256 depth = _mm256_movemask_ps(hit) == 0xFF
                           ? tt
                           : select(hit, tt, _mm256_div_ps(one, _mm256_loadu_ps(inv_w)));
  const V3 pos = {_mm256_add_ps(bc(r.eye.x), _mm256_mul_ps(depth, d.x)),
                  _mm256_add_ps(bc(r.eye.y), _mm256_mul_ps(depth, d.y)),
                  _mm256_add_ps(bc(r.eye.z), _mm256_mul_ps(depth, d.z))};
  // Two-sided: the normal faces the eye.
  V3 gn = t.gn();
  const V3 to_eye = {_mm256_sub_ps(bc(r.eye.x), pos.x), _mm256_sub_ps(bc(r.eye.y), pos.y),
                     _mm256_sub_ps(bc(r.eye.z), pos.z)};
  const __m256 flip_g = _mm256_and_ps(_mm256_cmp_ps(dot(gn, to_eye), zero, _CMP_LT_OQ), sign);
  gn = {_mm256_xor_ps(gn.x, flip_g), _mm256_xor_ps(gn.y, flip_g), _mm256_xor_ps(gn.z, flip_g)};
  store3(position, pos);
  store3(geo_normal, gn);
  _mm256_storeu_ps(depth_out, depth);
}

SL_AVX2 void resolve_run8_avx2(const ResolveRun8& r, int x, int y, const float* inv_w,
                               vec3* position, vec3* geo_normal, float* depth_out) {
  resolve8(r, SameTriangle{r}, x, y, inv_w, position, geo_normal, depth_out);
}

SL_AVX2 void resolve_lanes8_avx2(const ResolveRun8& camera, const ResolveLanes8& lanes, int x,
                                 int y, const float* inv_w, vec3* position, vec3* geo_normal,
                                 float* depth_out) {
  resolve8(camera, LaneTriangles(lanes, camera.eye), x, y, inv_w, position, geo_normal,
           depth_out);
}

#undef SL_AVX2

#define SL_AVX512 SL_TARGET("avx512f,avx512dq")

struct W3 {
  __m512 x, y, z;
};
SL_AVX512 inline __m512 bw(float v) { return _mm512_set1_ps(v); }
SL_AVX512 inline W3 load3w(const float (*v)[16]) {
  return {_mm512_load_ps(v[0]), _mm512_load_ps(v[1]), _mm512_load_ps(v[2])};
}
SL_AVX512 inline __m512 dotw(const W3& a, const W3& b) {
  return _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(a.x, b.x), _mm512_mul_ps(a.y, b.y)),
                       _mm512_mul_ps(a.z, b.z));
}
SL_AVX512 inline W3 crossw(const W3& a, const W3& b) {
  return {_mm512_sub_ps(_mm512_mul_ps(a.y, b.z), _mm512_mul_ps(b.y, a.z)),
          _mm512_sub_ps(_mm512_mul_ps(a.z, b.x), _mm512_mul_ps(b.z, a.x)),
          _mm512_sub_ps(_mm512_mul_ps(a.x, b.y), _mm512_mul_ps(b.x, a.y))};
}
SL_AVX512 inline void store3w(vec3* out, const W3& v) {
  alignas(64) float t[3][16];
  _mm512_store_ps(t[0], v.x);
  _mm512_store_ps(t[1], v.y);
  _mm512_store_ps(t[2], v.z);
  for (int i = 0; i < 16; ++i) out[i] = vec3(t[0][i], t[1][i], t[2][i]);
}
SL_AVX512 inline __m512 absw(__m512 v) {
  return _mm512_andnot_ps(_mm512_set1_ps(-0.0f), v);
}

// resolve8's operations on 16 lanes (compare masks where it blends).
SL_AVX512 void resolve_lanes16_avx512(const ResolveRun8& r, const ResolveLanes16& t, int x,
                                      int y, const float* inv_w, vec3* position,
                                      vec3* geo_normal, float* depth_out, uint32_t* mesh_id,
                                      uint32_t* prim_id, uint8_t* covered) {
  const __m512 zero = _mm512_setzero_ps(), one = bw(1.0f);
  const __m512 xs = _mm512_maskz_cvtepi32_ps(
      0xFFFF, _mm512_add_epi32(_mm512_set1_epi32(x), _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8,
                                                                       9, 10, 11, 12, 13, 14, 15)));
  const __m512 nx = _mm512_sub_ps(
      _mm512_mul_ps(_mm512_div_ps(_mm512_add_ps(xs, bw(0.5f)), bw(float(r.width))), bw(2.0f)), one);
  const float nys = (1.0f - (float(y) + 0.5f) / float(r.height) * 2.0f) * r.sy;
  const __m512 nxs = _mm512_mul_ps(nx, bw(r.sx));
  const W3 d = {_mm512_add_ps(_mm512_add_ps(bw(r.forward.x), _mm512_mul_ps(nxs, bw(r.right.x))), bw(nys * r.up.x)),
                _mm512_add_ps(_mm512_add_ps(bw(r.forward.y), _mm512_mul_ps(nxs, bw(r.right.y))), bw(nys * r.up.y)),
                _mm512_add_ps(_mm512_add_ps(bw(r.forward.z), _mm512_mul_ps(nxs, bw(r.right.z))), bw(nys * r.up.z))};
  const W3 pv = crossw(d, load3w(t.e2));
  const __m512 det = dotw(load3w(t.e1), pv);
  __m512 depth = _mm512_div_ps(one, _mm512_loadu_ps(inv_w));
  const __mmask16 ok_det = _mm512_cmp_ps_mask(absw(det), bw(1e-30f), _CMP_GT_OQ);
  const __m512 inv_det = _mm512_div_ps(one, det);
  const __m512 tt = _mm512_mul_ps(_mm512_load_ps(t.e2q), inv_det);
  const __mmask16 hit = __mmask16(ok_det &
                                  _mm512_cmp_ps_mask(absw(tt), bw(__builtin_inff()), _CMP_LT_OQ) &
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
  _mm_storeu_si128(reinterpret_cast<__m128i*>(covered),
                   _mm512_maskz_cvtepi32_epi8(0xFFFF, _mm512_maskz_mov_epi32(cov, _mm512_set1_epi32(1))));
}

SL_AVX512 inline void put3(float (*dst)[16], __mmask16 m, const vec3& v) {
  for (int c = 0; c < 3; ++c) _mm512_mask_storeu_ps(dst[c], m, bw(v[c]));
}

}  // namespace

SL_AVX512 uint32_t resolve_lanes16_runs(const uint32_t* ids, uint32_t* covered) {
  const __m512i v = _mm512_loadu_si512(ids);
  *covered = _mm512_cmpneq_epi32_mask(v, _mm512_set1_epi32(int(kNoPrimitive)));
  // Lane k against lane k − 1 (lane 0 against lane 15: bit 0 is set below whatever it gives).
  const __m512i prev = _mm512_maskz_alignr_epi32(0xFFFF, v, v, 15);
  return uint32_t(_mm512_cmpneq_epi32_mask(v, prev)) | 1u;
}

SL_AVX512 void resolve_lanes16_fill(ResolveLanes16& l, uint32_t mask, const vec3& e1,
                                    const vec3& e2, const vec3& gn, float e2q, uint32_t mesh,
                                    uint32_t prim) {
  const __mmask16 m = __mmask16(mask);
  _mm512_mask_storeu_epi32(l.mesh, m, _mm512_set1_epi32(int(mesh)));
  _mm512_mask_storeu_epi32(l.prim, m, _mm512_set1_epi32(int(prim)));
  put3(l.e1, m, e1);
  put3(l.e2, m, e2);
  put3(l.gn, m, gn);
  _mm512_mask_storeu_ps(l.e2q, m, bw(e2q));
}

namespace {
#undef SL_AVX512

}  // namespace
#endif

ResolveRun8Fn resolve_run8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (process_isa() >= Isa::avx2) return resolve_run8_avx2;
#endif
  return nullptr;
}

#ifndef SHADOWLAB_HAVE_X86
uint32_t resolve_lanes16_runs(const uint32_t*, uint32_t* covered) {
  *covered = 0;
  return 0;
}
void resolve_lanes16_fill(ResolveLanes16&, uint32_t, const vec3&, const vec3&, const vec3&, float,
                          uint32_t, uint32_t) {}
#endif

ResolveLanes16Fn resolve_lanes16_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (process_isa() == Isa::avx512) return resolve_lanes16_avx512;
#endif
  return nullptr;
}

ResolveLanes8Fn resolve_lanes8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (process_isa() >= Isa::avx2) return resolve_lanes8_avx2;
#endif
  return nullptr;
}

}  // namespace shadowlab

// File-local: a unity build compiles the next file in the same translation unit.
#undef SHADOWLAB_HAVE_X86
