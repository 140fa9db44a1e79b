#include "techniques/cube_lookup_simd.h"

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

#include "core/cpu_features.h"

namespace shadowlab {

#ifdef SHADOWLAB_HAVE_X86
namespace {

__attribute__((target("avx2"))) inline __m256 dot3(__m256 ax, __m256 ay, __m256 az, __m256 bx,
                                                  __m256 by, __m256 bz) {
  // ((ax·bx + ay·by) + az·bz): glm::dot's order.
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ax, bx), _mm256_mul_ps(ay, by)),
                       _mm256_mul_ps(az, bz));
}

__attribute__((target("avx2"))) void lookup8_avx2(const CubeLookupConsts& c, const float* pos,
                                                  const float* nrm, const uint8_t* covered_in,
                                                  float* mask, uint32_t* texels) {
  const __m256i stride3 = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  const __m256 px = _mm256_i32gather_ps(pos, stride3, 4);
  const __m256 py = _mm256_i32gather_ps(pos + 1, stride3, 4);
  const __m256 pz = _mm256_i32gather_ps(pos + 2, stride3, 4);
  const __m256 nx = _mm256_i32gather_ps(nrm, stride3, 4);
  const __m256 ny = _mm256_i32gather_ps(nrm + 1, stride3, 4);
  const __m256 nz = _mm256_i32gather_ps(nrm + 2, stride3, 4);
  int64_t cov8;
  std::memcpy(&cov8, covered_in, 8);
  const __m256i cov32 = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(cov8));
  const __m256 covered = _mm256_castsi256_ps(_mm256_cmpgt_epi32(cov32, _mm256_setzero_si256()));
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 lx = _mm256_set1_ps(c.light.x), ly = _mm256_set1_ps(c.light.y),
               lz = _mm256_set1_ps(c.light.z);
  // Facing test: dot(n, L − P) > 0.
  const __m256 facing = _mm256_cmp_ps(
      dot3(nx, ny, nz, _mm256_sub_ps(lx, px), _mm256_sub_ps(ly, py), _mm256_sub_ps(lz, pz)), zero,
      _CMP_GT_OQ);
  const __m256 tx = _mm256_sub_ps(px, lx), ty = _mm256_sub_ps(py, ly), tz = _mm256_sub_ps(pz, lz);
  const __m256 dist = _mm256_sqrt_ps(dot3(tx, ty, tz, tx, ty, tz));
  const __m256 positive = _mm256_cmp_ps(dist, zero, _CMP_GT_OQ);
  const __m256 active = _mm256_and_ps(_mm256_and_ps(covered, facing), positive);
  // Face: major axis, ties towards x then y, sign zero counts as positive (cube_face_of).
  const __m256 sign_mask = _mm256_set1_ps(-0.0f);
  const __m256 ax = _mm256_andnot_ps(sign_mask, tx), ay = _mm256_andnot_ps(sign_mask, ty),
               az = _mm256_andnot_ps(sign_mask, tz);
  const __m256 xmaj = _mm256_and_ps(_mm256_cmp_ps(ax, ay, _CMP_GE_OQ), _mm256_cmp_ps(ax, az, _CMP_GE_OQ));
  const __m256 ymaj = _mm256_andnot_ps(xmaj, _mm256_cmp_ps(ay, az, _CMP_GE_OQ));
  const __m256 zmaj = _mm256_andnot_ps(_mm256_or_ps(xmaj, ymaj), _mm256_castsi256_ps(_mm256_set1_epi32(-1)));
  const __m256 xneg = _mm256_cmp_ps(tx, zero, _CMP_LT_OQ), yneg = _mm256_cmp_ps(ty, zero, _CMP_LT_OQ),
               zneg = _mm256_cmp_ps(tz, zero, _CMP_LT_OQ);
  const __m256 neg = _mm256_blendv_ps(_mm256_blendv_ps(zneg, yneg, ymaj), xneg, xmaj);
  const __m256i face = _mm256_add_epi32(
      _mm256_blendv_epi8(_mm256_blendv_epi8(_mm256_set1_epi32(4), _mm256_set1_epi32(2),
                                            _mm256_castps_si256(ymaj)),
                         _mm256_setzero_si256(), _mm256_castps_si256(xmaj)),
      _mm256_and_si256(_mm256_castps_si256(neg), _mm256_set1_epi32(1)));
  // dot(dir, forward) = |major component|; right/up pick one signed component per face:
  //   +x: (−z, −y)  −x: (z, −y)  +y: (x, z)  −y: (x, −z)  +z: (x, −y)  −z: (−x, −y).
  const __m256 fdot = _mm256_blendv_ps(_mm256_blendv_ps(az, ay, ymaj), ax, xmaj);
  const __m256 mz = _mm256_xor_ps(tz, sign_mask), my = _mm256_xor_ps(ty, sign_mask),
               mx = _mm256_xor_ps(tx, sign_mask);
  const __m256 unum_x = _mm256_blendv_ps(mz, tz, xneg);  // +x: −z, −x: z
  const __m256 unum_z = _mm256_blendv_ps(tx, mx, zneg);  // +z: x, −z: −x
  const __m256 unum = _mm256_blendv_ps(_mm256_blendv_ps(unum_z, tx, ymaj), unum_x, xmaj);
  const __m256 vnum_y = _mm256_blendv_ps(tz, mz, yneg);  // +y: z, −y: −z
  const __m256 vnum = _mm256_blendv_ps(my, vnum_y, ymaj);  // x and z faces: −y
  (void)zmaj;
  const __m256 inv = _mm256_div_ps(one, fdot);
  const __m256 u = _mm256_mul_ps(unum, inv), v = _mm256_mul_ps(vnum, inv);
  const __m256 half = _mm256_set1_ps(0.5f), resf = _mm256_set1_ps(float(c.res));
  const __m256 sx = _mm256_mul_ps(_mm256_add_ps(_mm256_mul_ps(u, half), half), resf);
  const __m256 sy = _mm256_mul_ps(_mm256_sub_ps(half, _mm256_mul_ps(v, half)), resf);
  const __m256 m1 = _mm256_set1_ps(-1.0f);
  const __m256i hi = _mm256_set1_epi32(c.res - 1), lo = _mm256_setzero_si256();
  const __m256i itx = _mm256_min_epi32(_mm256_max_epi32(_mm256_cvttps_epi32(_mm256_max_ps(sx, m1)), lo), hi);
  const __m256i ity = _mm256_min_epi32(_mm256_max_epi32(_mm256_cvttps_epi32(_mm256_max_ps(sy, m1)), lo), hi);
  const __m256i resv = _mm256_set1_epi32(c.res);
  const __m256i in_face = _mm256_add_epi32(_mm256_mullo_epi32(ity, resv), itx);
  const __m256i texel = _mm256_add_epi32(_mm256_mullo_epi32(face, _mm256_mullo_epi32(resv, resv)), in_face);
  // Bias and receiver depth, in the scalar path's order of operations.
  const __m256 ndot = dot3(nx, ny, nz, _mm256_xor_ps(tx, sign_mask), _mm256_xor_ps(ty, sign_mask),
                           _mm256_xor_ps(tz, sign_mask));
  const __m256 cos_t = _mm256_min_ps(_mm256_max_ps(_mm256_div_ps(ndot, dist), _mm256_set1_ps(1e-4f)), one);
  const __m256 tan_t = _mm256_min_ps(
      _mm256_div_ps(_mm256_sqrt_ps(_mm256_sub_ps(one, _mm256_mul_ps(cos_t, cos_t))), cos_t),
      _mm256_set1_ps(10.0f));
  const __m256 bias = _mm256_add_ps(_mm256_set1_ps(c.bias),
                                    _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(c.slope_k), dist), tan_t));
  const __m256 receiver = _mm256_mul_ps(_mm256_sub_ps(dist, bias), _mm256_set1_ps(c.inv_far));
  // Stored distance: gathered only for active lanes (an inactive lane's face may not exist).
  alignas(32) int32_t face_a[8], idx_a[8], act_a[8];
  alignas(32) float stored_a[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(face_a), face);
  _mm256_store_si256(reinterpret_cast<__m256i*>(idx_a), in_face);
  _mm256_store_si256(reinterpret_cast<__m256i*>(act_a), _mm256_castps_si256(active));
  for (int i = 0; i < 8; ++i) stored_a[i] = act_a[i] ? c.face_depth[face_a[i]][idx_a[i]] : 0.0f;
  const __m256 lit = _mm256_and_ps(_mm256_cmp_ps(receiver, _mm256_load_ps(stored_a), _CMP_LE_OQ), one);
  // Mask: uncovered 1, facing away 0, at the light 1, else lit.
  __m256 m = _mm256_blendv_ps(one, lit, active);
  m = _mm256_blendv_ps(m, zero, _mm256_andnot_ps(facing, covered));
  _mm256_storeu_ps(mask, m);
  if (texels) {
    const __m256i none = _mm256_set1_epi32(-1);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(texels),
                        _mm256_blendv_epi8(none, texel, _mm256_castps_si256(active)));
  }
}

}  // namespace
#endif

CubeLookup8Fn cube_lookup8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return lookup8_avx2;
#endif
  return nullptr;
}

}  // namespace shadowlab
