// The AVX2 paths of raster/gbuffer_resolve_simd.h (8 pixels; the AVX-512 table uses them too).
// Compiled with -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

#include "core/gbuffer.h"
#include "raster/gbuffer_resolve_simd.h"

namespace shadowlab::gbuffer_resolve_avx2 {

struct V3 {
  __m256 x, y, z;
};

[[gnu::always_inline]] inline __m256 bc(float v) { return _mm256_set1_ps(v); }
[[gnu::always_inline]] inline V3 bc3(const vec3& v) { return {bc(v.x), bc(v.y), bc(v.z)}; }
// glm::dot order: (a.x·b.x + a.y·b.y) + a.z·b.z.
[[gnu::always_inline]] inline __m256 dot(const V3& a, const V3& b) {
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y)),
                       _mm256_mul_ps(a.z, b.z));
}
// glm::cross: (x.y·y.z − y.y·x.z, x.z·y.x − y.z·x.x, x.x·y.y − y.x·x.y).
[[gnu::always_inline]] inline V3 cross(const V3& a, const V3& b) {
  return {_mm256_sub_ps(_mm256_mul_ps(a.y, b.z), _mm256_mul_ps(b.y, a.z)),
          _mm256_sub_ps(_mm256_mul_ps(a.z, b.x), _mm256_mul_ps(b.z, a.x)),
          _mm256_sub_ps(_mm256_mul_ps(a.x, b.y), _mm256_mul_ps(b.x, a.y))};
}
// ((l0·a + l1·b) + l2·c), componentwise: glm's l.x*a + l.y*b + l.z*c.
[[gnu::always_inline]] inline __m256 interp(__m256 l0, __m256 l1, __m256 l2, float a, float b,
                                            float c) {
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(l0, bc(a)), _mm256_mul_ps(l1, bc(b))),
                       _mm256_mul_ps(l2, bc(c)));
}
[[gnu::always_inline]] inline __m256 select(__m256 mask, __m256 if_true, __m256 if_false) {
  return _mm256_blendv_ps(if_false, if_true, mask);
}
[[gnu::always_inline]] inline void store3(vec3* out, const V3& v) {
  alignas(32) float t[3][8];
  _mm256_store_ps(t[0], v.x);
  _mm256_store_ps(t[1], v.y);
  _mm256_store_ps(t[2], v.z);
  float* o = &out[0].x;  // packed vec3s (no glm function in this file)
  for (int i = 0; i < 8; ++i) {
    o[3 * i] = t[0][i];
    o[3 * i + 1] = t[1][i];
    o[3 * i + 2] = t[2][i];
  }
}

[[gnu::always_inline]] inline V3 load3(const float (*v)[8]) {
  return {_mm256_load_ps(v[0]), _mm256_load_ps(v[1]), _mm256_load_ps(v[2])};
}

// The triangle terms of one triangle for all 8 lanes (broadcasts).
struct SameTriangle {
  const ResolveRun8& r;
  [[gnu::always_inline]] V3 e1() const { return bc3(r.e1); }
  [[gnu::always_inline]] V3 e2() const { return bc3(r.e2); }
  [[gnu::always_inline]] V3 gn() const { return bc3(r.gn); }
  [[gnu::always_inline]] __m256 e2q() const { return bc(r.e2q); }
};

[[gnu::always_inline]] inline V3 sub3(const V3& a, const V3& b) {
  return {_mm256_sub_ps(a.x, b.x), _mm256_sub_ps(a.y, b.y), _mm256_sub_ps(a.z, b.z)};
}

// Each lane's own triangle: the terms load_triangle (gbuffer_pass.cpp) computes, from the
// lanes' vertices with its operations in its order (glm's -, cross, dot, length and /).
struct LaneTriangles {
  V3 e1_, e2_, gn_;
  __m256 e2q_;
  [[gnu::always_inline]] LaneTriangles(const ResolveLanes8& l, const vec3& eye) {
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
  [[gnu::always_inline]] V3 e1() const { return e1_; }
  [[gnu::always_inline]] V3 e2() const { return e2_; }
  [[gnu::always_inline]] V3 gn() const { return gn_; }
  [[gnu::always_inline]] __m256 e2q() const { return e2q_; }
};

// The scalar resolve's operations for 8 pixels (gbuffer_pass.cpp), triangle terms from `t`.
template <class Terms>
[[gnu::always_inline]] inline void resolve8(const ResolveRun8& r, const Terms& t, int x, int y,
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
  const __m256 hit =
      _mm256_and_ps(_mm256_and_ps(ok_det, finite), _mm256_cmp_ps(tt, zero, _CMP_GT_OQ));
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

void run8(const ResolveRun8& r, int x, int y, const float* inv_w, vec3* position, vec3* geo_normal,
          float* depth_out) {
  resolve8(r, SameTriangle{r}, x, y, inv_w, position, geo_normal, depth_out);
}

void lanes8(const ResolveRun8& camera, const ResolveLanes8& lanes, int x, int y, const float* inv_w,
            vec3* position, vec3* geo_normal, float* depth_out) {
  resolve8(camera, LaneTriangles(lanes, camera.eye), x, y, inv_w, position, geo_normal, depth_out);
}

}  // namespace shadowlab::gbuffer_resolve_avx2
#endif
