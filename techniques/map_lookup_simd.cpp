#include "techniques/map_lookup_simd.h"

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

#include "core/cpu_features.h"
#include "core/error.h"
#include "core/projector.h"

namespace shadowlab {

MapLookupConsts map_lookup_consts(const Scene& scene, const FaceLayout& layout, const MapParams& p,
                                  const std::vector<std::vector<float>>& face_depth) {
  SL_CHECK(layout.faces.size() <= 4);
  MapLookupConsts c;
  c.light = scene.light.position;
  c.inv_far = 1.0f / scene.light.far;
  c.bias = p.bias;
  c.slope_k = p.slope * map_reach(p);
  c.plane_texel = face_texel_plane_size(layout.faces[0]);
  c.tetra = layout.kind == FaceLayoutKind::Tetrahedron;
  c.projector = layout.kind == FaceLayoutKind::Projector;
  if (c.projector) {
    const ProjectorFrame fr = projector_frame(scene.projector);
    c.proj_forward = fr.forward;
    c.proj_right = fr.right;
    c.proj_up = fr.up;
    c.proj_tan_x = fr.tan_x;
    c.proj_tan_y = fr.tan_y;
  }
  for (size_t i = 0; i < layout.faces.size(); ++i) {
    const LightFace& f = layout.faces[i];
    for (int k = 0; k < 3; ++k) {
      c.fwd[k][i] = f.forward[k];
      c.right[k][i] = f.right[k];
      c.up[k][i] = f.up[k];
    }
    c.left[i] = f.left;
    c.range_u[i] = f.right_edge - f.left;
    c.top[i] = f.top;
    c.range_v[i] = f.top - f.bottom;
    c.width_f[i] = float(f.width);
    c.height_f[i] = float(f.height);
    c.width[i] = f.width;
    c.height[i] = f.height;
    c.base[i] = int32_t(i * f.texel_count());
    c.depth[i] = face_depth[i].empty() ? nullptr : face_depth[i].data();
  }
  return c;
}

#ifdef SHADOWLAB_HAVE_X86
namespace {

#define SL_AVX2 __attribute__((target("avx2")))

SL_AVX2 inline __m256 dot3(__m256 ax, __m256 ay, __m256 az, __m256 bx, __m256 by, __m256 bz) {
  // ((ax·bx + ay·by) + az·bz): glm::dot's order.
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ax, bx), _mm256_mul_ps(ay, by)),
                       _mm256_mul_ps(az, bz));
}

SL_AVX2 inline __m256 lane(const float* table, __m256i face) {
  return _mm256_permutevar8x32_ps(_mm256_load_ps(table), face);
}

SL_AVX2 void lookup8_avx2(const MapLookupConsts& c, const float* pos, const float* nrm,
                          const uint8_t* covered_in, float* mask, uint32_t* texels) {
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
  const __m256 sign_mask = _mm256_set1_ps(-0.0f);
  const __m256 lx = _mm256_set1_ps(c.light.x), ly = _mm256_set1_ps(c.light.y),
               lz = _mm256_set1_ps(c.light.z);
  // Facing test: dot(n, L − P) > 0 (faces_light).
  const __m256 facing = _mm256_cmp_ps(
      dot3(nx, ny, nz, _mm256_sub_ps(lx, px), _mm256_sub_ps(ly, py), _mm256_sub_ps(lz, pz)), zero,
      _CMP_GT_OQ);
  const __m256 tx = _mm256_sub_ps(px, lx), ty = _mm256_sub_ps(py, ly), tz = _mm256_sub_ps(pz, lz);
  __m256 active = _mm256_and_ps(covered, facing);
  if (c.projector) {
    // projector_slide_coords: in front of the projector and inside [0, 1]² of its slide.
    const __m256 z = dot3(tx, ty, tz, _mm256_set1_ps(c.proj_forward.x),
                          _mm256_set1_ps(c.proj_forward.y), _mm256_set1_ps(c.proj_forward.z));
    const __m256 half = _mm256_set1_ps(0.5f);
    const __m256 dr = dot3(tx, ty, tz, _mm256_set1_ps(c.proj_right.x),
                           _mm256_set1_ps(c.proj_right.y), _mm256_set1_ps(c.proj_right.z));
    const __m256 du = dot3(tx, ty, tz, _mm256_set1_ps(c.proj_up.x), _mm256_set1_ps(c.proj_up.y),
                           _mm256_set1_ps(c.proj_up.z));
    const __m256 sx = _mm256_add_ps(
        half, _mm256_div_ps(_mm256_mul_ps(half, dr), _mm256_mul_ps(z, _mm256_set1_ps(c.proj_tan_x))));
    const __m256 sy = _mm256_sub_ps(
        half, _mm256_div_ps(_mm256_mul_ps(half, du), _mm256_mul_ps(z, _mm256_set1_ps(c.proj_tan_y))));
    const __m256 inside = _mm256_and_ps(
        _mm256_and_ps(_mm256_cmp_ps(z, zero, _CMP_GT_OQ),
                      _mm256_and_ps(_mm256_cmp_ps(sx, zero, _CMP_GE_OQ), _mm256_cmp_ps(sx, one, _CMP_LE_OQ))),
        _mm256_and_ps(_mm256_cmp_ps(sy, zero, _CMP_GE_OQ), _mm256_cmp_ps(sy, one, _CMP_LE_OQ)));
    active = _mm256_and_ps(active, inside);
  }
  const __m256 dist = _mm256_sqrt_ps(dot3(tx, ty, tz, tx, ty, tz));
  // Face: argmax of dot(dir, normal) over the tetrahedron's faces, ties to the lower index.
  __m256i face = _mm256_setzero_si256();
  if (c.tetra) {
    __m256 best = dot3(tx, ty, tz, _mm256_set1_ps(c.fwd[0][0]), _mm256_set1_ps(c.fwd[1][0]),
                       _mm256_set1_ps(c.fwd[2][0]));
    for (int i = 1; i < 4; ++i) {
      const __m256 d = dot3(tx, ty, tz, _mm256_set1_ps(c.fwd[0][i]), _mm256_set1_ps(c.fwd[1][i]),
                            _mm256_set1_ps(c.fwd[2][i]));
      const __m256 better = _mm256_cmp_ps(d, best, _CMP_GT_OQ);
      best = _mm256_blendv_ps(best, d, better);
      face = _mm256_blendv_epi8(face, _mm256_set1_epi32(i), _mm256_castps_si256(better));
    }
  }
  // Texel coordinates in the face (face_texel_coords).
  const __m256 axial = dot3(tx, ty, tz, lane(c.fwd[0], face), lane(c.fwd[1], face), lane(c.fwd[2], face));
  const __m256 inv = _mm256_div_ps(one, axial);
  const __m256 u = _mm256_mul_ps(dot3(tx, ty, tz, lane(c.right[0], face), lane(c.right[1], face),
                                      lane(c.right[2], face)), inv);
  const __m256 v = _mm256_mul_ps(dot3(tx, ty, tz, lane(c.up[0], face), lane(c.up[1], face),
                                      lane(c.up[2], face)), inv);
  const __m256 sx = _mm256_mul_ps(
      _mm256_div_ps(_mm256_sub_ps(u, lane(c.left, face)), lane(c.range_u, face)), lane(c.width_f, face));
  const __m256 sy = _mm256_mul_ps(
      _mm256_div_ps(_mm256_sub_ps(lane(c.top, face), v), lane(c.range_v, face)), lane(c.height_f, face));
  const __m256 m1 = _mm256_set1_ps(-1.0f);
  const __m256i w = _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(c.width)), face);
  const __m256i h = _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(c.height)), face);
  const __m256i base = _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(c.base)), face);
  const __m256i lo = _mm256_setzero_si256(), one_i = _mm256_set1_epi32(1);
  const __m256i itx = _mm256_min_epi32(
      _mm256_max_epi32(_mm256_cvttps_epi32(_mm256_max_ps(sx, m1)), lo), _mm256_sub_epi32(w, one_i));
  const __m256i ity = _mm256_min_epi32(
      _mm256_max_epi32(_mm256_cvttps_epi32(_mm256_max_ps(sy, m1)), lo), _mm256_sub_epi32(h, one_i));
  const __m256i in_face = _mm256_add_epi32(_mm256_mullo_epi32(ity, w), itx);
  const __m256i texel = _mm256_add_epi32(base, in_face);
  // Bias and receiver depth, in make_receiver's order of operations.
  const __m256 ndot = dot3(nx, ny, nz, _mm256_xor_ps(tx, sign_mask), _mm256_xor_ps(ty, sign_mask),
                           _mm256_xor_ps(tz, sign_mask));
  const __m256 cos_t =
      _mm256_min_ps(_mm256_max_ps(_mm256_div_ps(ndot, dist), _mm256_set1_ps(1e-4f)), one);
  const __m256 tan_t = _mm256_min_ps(
      _mm256_div_ps(_mm256_sqrt_ps(_mm256_sub_ps(one, _mm256_mul_ps(cos_t, cos_t))), cos_t),
      _mm256_set1_ps(10.0f));
  const __m256 slope_bias = _mm256_mul_ps(
      _mm256_mul_ps(_mm256_set1_ps(c.slope_k), _mm256_mul_ps(_mm256_set1_ps(c.plane_texel), axial)), tan_t);
  const __m256 receiver = _mm256_mul_ps(
      _mm256_sub_ps(dist, _mm256_add_ps(_mm256_set1_ps(c.bias), slope_bias)), _mm256_set1_ps(c.inv_far));
  // Stored distance: read only for active lanes (an inactive lane's face may not exist).
  alignas(32) int32_t face_a[8], idx_a[8], act_a[8];
  alignas(32) float stored_a[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(face_a), face);
  _mm256_store_si256(reinterpret_cast<__m256i*>(idx_a), in_face);
  _mm256_store_si256(reinterpret_cast<__m256i*>(act_a), _mm256_castps_si256(active));
  for (int i = 0; i < 8; ++i) stored_a[i] = act_a[i] ? c.depth[face_a[i]][idx_a[i]] : 0.0f;
  const __m256 lit = _mm256_and_ps(_mm256_cmp_ps(receiver, _mm256_load_ps(stored_a), _CMP_LE_OQ), one);
  // Mask: uncovered 1, covered but not looked up 0, else lit.
  const __m256 m = _mm256_blendv_ps(_mm256_blendv_ps(one, zero, covered), lit, active);
  _mm256_storeu_ps(mask, m);
  if (texels)
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(texels),
                        _mm256_blendv_epi8(_mm256_set1_epi32(-1), texel, _mm256_castps_si256(active)));
}

}  // namespace
#endif

MapLookup8Fn map_lookup8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return lookup8_avx2;
#endif
  return nullptr;
}

}  // namespace shadowlab
