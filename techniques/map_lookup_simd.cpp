#include "techniques/map_lookup_simd.h"

#include <algorithm>
#include <climits>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#define SHADOWLAB_HAVE_X86 1
#endif

#include "core/cpu_features.h"
#include "core/error.h"
#include "core/projector.h"
#include "core/simd_target.h"
#include "techniques/chebyshev.h"

namespace shadowlab {

namespace {

template <class Planes>
PlaneGather gather_planes(const Planes& planes) {
  PlaneGather g;
  uintptr_t lowest = UINTPTR_MAX;
  for (const auto& d : planes)
    if (!d.empty()) lowest = std::min(lowest, reinterpret_cast<uintptr_t>(d.data()));
  if (lowest == UINTPTR_MAX || planes.size() > 8) return g;
  g.ok = true;
  g.base = reinterpret_cast<const float*>(lowest);
  for (size_t i = 0; i < planes.size(); ++i) {
    if (planes[i].empty()) continue;
    const uintptr_t bytes = reinterpret_cast<uintptr_t>(planes[i].data()) - lowest;
    const uintptr_t floats = bytes / sizeof(float);
    if (bytes % sizeof(float) != 0 || floats + planes[i].size() > uintptr_t(INT32_MAX))
      g.ok = false;
    else
      g.offset[i] = int32_t(floats);
  }
  return g;
}

}  // namespace

PlaneGather plane_gather(const std::vector<std::vector<float>>& planes) {
  return gather_planes(planes);
}

PlaneGather plane_gather(const std::vector<LineAlignedFloats>& planes) {
  return gather_planes(planes);
}

MapLookupConsts map_lookup_consts(const Scene& scene, const FaceLayout& layout, const MapParams& p,
                                  const std::vector<LineAlignedFloats>& face_depth) {
  SL_CHECK(layout.faces.size() <= 8);
  MapLookupConsts c;
  c.light = scene.light.position;
  c.inv_far = 1.0f / scene.light.far;
  c.bias = p.bias;
  c.slope_k = p.slope * map_reach(p);
  c.plane_texel = face_texel_plane_size(layout.faces[0]);
  c.kind = layout.kind;
  if (c.kind == FaceLayoutKind::Projector) {
    const ProjectorFrame fr = projector_frame(scene.projector);
    c.proj_forward = fr.forward;
    c.proj_right = fr.right;
    c.proj_up = fr.up;
    c.proj_tan_x = fr.tan_x;
    c.proj_tan_y = fr.tan_y;
  }
  // The rendered faces' storage, gathered from one base.
  const PlaneGather pg = plane_gather(face_depth);
  c.gather_ok = pg.ok;
  c.depth_base = pg.base;
  for (int i = 0; i < 8; ++i) c.offset[i] = pg.offset[i];
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
  }
  return c;
}

#ifdef SHADOWLAB_HAVE_X86
namespace {

#define SL_AVX2 SL_TARGET("avx2")

SL_AVX2 inline __m256 dot3(__m256 ax, __m256 ay, __m256 az, __m256 bx, __m256 by, __m256 bz) {
  // ((ax·bx + ay·by) + az·bz): glm::dot's order.
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ax, bx), _mm256_mul_ps(ay, by)),
                       _mm256_mul_ps(az, bz));
}
SL_AVX2 inline __m256 lane(const float* table, __m256i face) {
  return _mm256_permutevar8x32_ps(_mm256_load_ps(table), face);
}
SL_AVX2 inline __m256i lane_i(const int32_t* table, __m256i face) {
  return _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(table)), face);
}
SL_AVX2 inline __m256 set(float v) { return _mm256_set1_ps(v); }

// floor_int (map_receiver.h): truncate, step down where the truncation is above g.
SL_AVX2 inline __m256i floor_i(__m256 g) {
  const __m256i i = _mm256_cvttps_epi32(g);
  const __m256 above = _mm256_cmp_ps(_mm256_cvtepi32_ps(i), g, _CMP_GT_OQ);
  return _mm256_add_epi32(i, _mm256_castps_si256(above));  // + (-1) where above
}

// 8 packed vec3 (x0 y0 z0 x1 … z7) into x, y, z lanes: three loads, two blends and a permute
// per component (cheaper than three 8-lane gathers; the values are the same floats).
SL_AVX2 inline void load_vec3x8(const float* p, __m256& x, __m256& y, __m256& z) {
  const __m256 a = _mm256_loadu_ps(p), b = _mm256_loadu_ps(p + 8), c = _mm256_loadu_ps(p + 16);
  // Lane k of a/b/c holds component (8·block + k) mod 3 of point (8·block + k) / 3.
  const __m256 tx = _mm256_blend_ps(_mm256_blend_ps(a, b, 0x92), c, 0x24);  // a0 b1 c2 a3 b4 c5 a6 b7
  const __m256 ty = _mm256_blend_ps(_mm256_blend_ps(a, b, 0x24), c, 0x49);  // c0 a1 b2 c3 a4 b5 c6 a7
  const __m256 tz = _mm256_blend_ps(_mm256_blend_ps(a, b, 0x49), c, 0x92);  // b0 c1 a2 b3 c4 a5 b6 c7
  x = _mm256_permutevar8x32_ps(tx, _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5));
  y = _mm256_permutevar8x32_ps(ty, _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6));
  z = _mm256_permutevar8x32_ps(tz, _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7));
}

struct R8 {
  __m256 covered, active;  // all-ones lanes
  __m256 sx, sy, depth;
  __m256i face, texel;
};

// The first half of make_receiver() with lookup_faces()' gates: which lanes look up (covered,
// facing the light, inside the projector's frustum), the light-to-point vector and the face.
struct Front {
  __m256 covered, active;
  __m256 tx, ty, tz, nx, ny, nz;
  __m256i face;
};

SL_AVX2 inline Front front(const MapLookupConsts& c, const float* pos, const float* nrm,
                           const uint8_t* covered_in) {
  __m256 px, py, pz;
  load_vec3x8(pos, px, py, pz);
  Front f;
  load_vec3x8(nrm, f.nx, f.ny, f.nz);
  int64_t cov8;
  std::memcpy(&cov8, covered_in, 8);
  const __m256i cov32 = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(cov8));
  f.covered = _mm256_castsi256_ps(_mm256_cmpgt_epi32(cov32, _mm256_setzero_si256()));
  const __m256 zero = _mm256_setzero_ps(), one = set(1.0f);
  const __m256 sign_mask = set(-0.0f);
  const __m256 lx = set(c.light.x), ly = set(c.light.y), lz = set(c.light.z);
  // Facing test: dot(n, L − P) > 0 (faces_light).
  const __m256 facing = _mm256_cmp_ps(
      dot3(f.nx, f.ny, f.nz, _mm256_sub_ps(lx, px), _mm256_sub_ps(ly, py), _mm256_sub_ps(lz, pz)),
      zero, _CMP_GT_OQ);
  const __m256 tx = _mm256_sub_ps(px, lx), ty = _mm256_sub_ps(py, ly), tz = _mm256_sub_ps(pz, lz);
  f.tx = tx;
  f.ty = ty;
  f.tz = tz;
  f.active = _mm256_and_ps(f.covered, facing);
  if (c.kind == FaceLayoutKind::Projector) {
    // projector_slide_coords: in front of the projector and inside [0, 1]² of its slide.
    const __m256 z = dot3(tx, ty, tz, set(c.proj_forward.x), set(c.proj_forward.y), set(c.proj_forward.z));
    const __m256 half = set(0.5f);
    const __m256 dr = dot3(tx, ty, tz, set(c.proj_right.x), set(c.proj_right.y), set(c.proj_right.z));
    const __m256 du = dot3(tx, ty, tz, set(c.proj_up.x), set(c.proj_up.y), set(c.proj_up.z));
    const __m256 sx = _mm256_add_ps(half, _mm256_div_ps(_mm256_mul_ps(half, dr), _mm256_mul_ps(z, set(c.proj_tan_x))));
    const __m256 sy = _mm256_sub_ps(half, _mm256_div_ps(_mm256_mul_ps(half, du), _mm256_mul_ps(z, set(c.proj_tan_y))));
    const __m256 inside = _mm256_and_ps(
        _mm256_and_ps(_mm256_cmp_ps(z, zero, _CMP_GT_OQ),
                      _mm256_and_ps(_mm256_cmp_ps(sx, zero, _CMP_GE_OQ), _mm256_cmp_ps(sx, one, _CMP_LE_OQ))),
        _mm256_and_ps(_mm256_cmp_ps(sy, zero, _CMP_GE_OQ), _mm256_cmp_ps(sy, one, _CMP_LE_OQ)));
    f.active = _mm256_and_ps(f.active, inside);
  }
  __m256i face = _mm256_setzero_si256();
  if (c.kind == FaceLayoutKind::Cube) {
    // cube_face_of: major axis, ties towards x then y, a zero component counts as positive.
    const __m256 ax = _mm256_andnot_ps(sign_mask, tx), ay = _mm256_andnot_ps(sign_mask, ty),
                 az = _mm256_andnot_ps(sign_mask, tz);
    const __m256 xmaj = _mm256_and_ps(_mm256_cmp_ps(ax, ay, _CMP_GE_OQ), _mm256_cmp_ps(ax, az, _CMP_GE_OQ));
    const __m256 ymaj = _mm256_andnot_ps(xmaj, _mm256_cmp_ps(ay, az, _CMP_GE_OQ));
    const __m256 neg = _mm256_blendv_ps(
        _mm256_blendv_ps(_mm256_cmp_ps(tz, zero, _CMP_LT_OQ), _mm256_cmp_ps(ty, zero, _CMP_LT_OQ), ymaj),
        _mm256_cmp_ps(tx, zero, _CMP_LT_OQ), xmaj);
    face = _mm256_add_epi32(
        _mm256_blendv_epi8(_mm256_blendv_epi8(_mm256_set1_epi32(4), _mm256_set1_epi32(2),
                                              _mm256_castps_si256(ymaj)),
                           _mm256_setzero_si256(), _mm256_castps_si256(xmaj)),
        _mm256_and_si256(_mm256_castps_si256(neg), _mm256_set1_epi32(1)));
  } else if (c.kind == FaceLayoutKind::DualParaboloid) {
    // face_of: the hemisphere of face 0 (dir·forward >= 0, the rim included) or face 1.
    const __m256 d = dot3(tx, ty, tz, set(c.fwd[0][0]), set(c.fwd[1][0]), set(c.fwd[2][0]));
    face = _mm256_andnot_si256(_mm256_castps_si256(_mm256_cmp_ps(d, zero, _CMP_GE_OQ)),
                               _mm256_set1_epi32(1));
  } else if (c.kind == FaceLayoutKind::Tetrahedron) {
    // argmax of dot(dir, normal), ties to the lower index.
    __m256 best = dot3(tx, ty, tz, set(c.fwd[0][0]), set(c.fwd[1][0]), set(c.fwd[2][0]));
    for (int i = 1; i < 4; ++i) {
      const __m256 d = dot3(tx, ty, tz, set(c.fwd[0][i]), set(c.fwd[1][i]), set(c.fwd[2][i]));
      const __m256 better = _mm256_cmp_ps(d, best, _CMP_GT_OQ);
      best = _mm256_blendv_ps(best, d, better);
      face = _mm256_blendv_epi8(face, _mm256_set1_epi32(i), _mm256_castps_si256(better));
    }
  }
  f.face = face;
  return f;
}

// Continuous texel coordinates of the lanes in their faces (face_texel_coords); `axial` is
// dot(to_p, forward), which the slope bias reuses.
SL_AVX2 inline void texel_coords(const MapLookupConsts& c, const Front& f, __m256& sx, __m256& sy,
                                 __m256& axial) {
  const __m256i face = f.face;
  axial = dot3(f.tx, f.ty, f.tz, lane(c.fwd[0], face), lane(c.fwd[1], face), lane(c.fwd[2], face));
  // The paraboloid map divides by |dir| + dir·forward, the gnomonic one by dir·forward.
  const __m256 den = c.kind == FaceLayoutKind::DualParaboloid
                         ? _mm256_add_ps(_mm256_sqrt_ps(dot3(f.tx, f.ty, f.tz, f.tx, f.ty, f.tz)), axial)
                         : axial;
  const __m256 inv = _mm256_div_ps(set(1.0f), den);
  const __m256 u = _mm256_mul_ps(dot3(f.tx, f.ty, f.tz, lane(c.right[0], face), lane(c.right[1], face),
                                      lane(c.right[2], face)), inv);
  const __m256 v = _mm256_mul_ps(dot3(f.tx, f.ty, f.tz, lane(c.up[0], face), lane(c.up[1], face),
                                      lane(c.up[2], face)), inv);
  sx = _mm256_mul_ps(_mm256_div_ps(_mm256_sub_ps(u, lane(c.left, face)), lane(c.range_u, face)),
                     lane(c.width_f, face));
  sy = _mm256_mul_ps(_mm256_div_ps(_mm256_sub_ps(lane(c.top, face), v), lane(c.range_v, face)),
                     lane(c.height_f, face));
}

// make_receiver() and lookup_faces()' gates for 8 pixels (no normal offset).
SL_AVX2 inline R8 receivers(const MapLookupConsts& c, const float* pos, const float* nrm,
                            const uint8_t* covered_in) {
  const Front f = front(c, pos, nrm, covered_in);
  R8 r;
  r.covered = f.covered;
  r.active = f.active;
  r.face = f.face;
  const __m256 one = set(1.0f), sign_mask = set(-0.0f);
  __m256 axial;
  texel_coords(c, f, r.sx, r.sy, axial);
  const __m256 m1 = set(-1.0f);
  const __m256i w = lane_i(c.width, f.face), h = lane_i(c.height, f.face);
  const __m256i lo = _mm256_setzero_si256(), one_i = _mm256_set1_epi32(1);
  const __m256i itx = _mm256_min_epi32(
      _mm256_max_epi32(_mm256_cvttps_epi32(_mm256_max_ps(r.sx, m1)), lo), _mm256_sub_epi32(w, one_i));
  const __m256i ity = _mm256_min_epi32(
      _mm256_max_epi32(_mm256_cvttps_epi32(_mm256_max_ps(r.sy, m1)), lo), _mm256_sub_epi32(h, one_i));
  r.texel = _mm256_add_epi32(lane_i(c.base, f.face), _mm256_add_epi32(_mm256_mullo_epi32(ity, w), itx));
  // Bias and receiver depth, in make_receiver's order of operations.
  const __m256 dist = _mm256_sqrt_ps(dot3(f.tx, f.ty, f.tz, f.tx, f.ty, f.tz));
  const __m256 ndot = dot3(f.nx, f.ny, f.nz, _mm256_xor_ps(f.tx, sign_mask),
                           _mm256_xor_ps(f.ty, sign_mask), _mm256_xor_ps(f.tz, sign_mask));
  const __m256 cos_t = _mm256_min_ps(_mm256_max_ps(_mm256_div_ps(ndot, dist), set(1e-4f)), one);
  const __m256 tan_t = _mm256_min_ps(
      _mm256_div_ps(_mm256_sqrt_ps(_mm256_sub_ps(one, _mm256_mul_ps(cos_t, cos_t))), cos_t), set(10.0f));
  const __m256 k = set(c.slope_k), plane = set(c.plane_texel);
  __m256 slope_bias;
  if (c.kind == FaceLayoutKind::Cube) {
    slope_bias = _mm256_mul_ps(_mm256_mul_ps(_mm256_mul_ps(k, plane), dist), tan_t);
  } else if (c.kind == FaceLayoutKind::DualParaboloid) {
    // plane texel × dist × 2/(1 + u² + v²), (u, v) = face_plane_coords(st).
    const __m256i face = f.face;
    const __m256 u = _mm256_add_ps(lane(c.left, face), _mm256_mul_ps(_mm256_div_ps(r.sx, lane(c.width_f, face)),
                                                                     lane(c.range_u, face)));
    const __m256 v = _mm256_sub_ps(lane(c.top, face), _mm256_mul_ps(_mm256_div_ps(r.sy, lane(c.height_f, face)),
                                                                    lane(c.range_v, face)));
    const __m256 q = _mm256_add_ps(one, _mm256_add_ps(_mm256_mul_ps(u, u), _mm256_mul_ps(v, v)));
    const __m256 size = _mm256_div_ps(_mm256_mul_ps(_mm256_mul_ps(plane, dist), set(2.0f)), q);
    slope_bias = _mm256_mul_ps(_mm256_mul_ps(k, size), tan_t);
  } else {
    slope_bias = _mm256_mul_ps(_mm256_mul_ps(k, _mm256_mul_ps(plane, axial)), tan_t);
  }
  r.depth = _mm256_mul_ps(_mm256_sub_ps(dist, _mm256_add_ps(set(c.bias), slope_bias)), set(c.inv_far));
  return r;
}

// Lanes whose N×N footprint at (sx, sy) lies inside their face's image (pcf_taps_inside), with
// the footprint's first column/row and fractions.
struct Footprint {
  __m256 inside;
  __m256i x0, y0;
  __m256 fx, fy;
};
SL_AVX2 inline Footprint footprint(const MapLookupConsts& c, int pcf, __m256 sx, __m256 sy, __m256i face) {
  const __m256 half_px = set(0.5f);
  const __m256 gx = _mm256_sub_ps(sx, half_px), gy = _mm256_sub_ps(sy, half_px);
  const __m256i bx = floor_i(gx), by = floor_i(gy);
  Footprint fp;
  fp.fx = _mm256_sub_ps(gx, _mm256_cvtepi32_ps(bx));
  fp.fy = _mm256_sub_ps(gy, _mm256_cvtepi32_ps(by));
  const __m256i half = _mm256_set1_epi32((pcf - 1) / 2), n = _mm256_set1_epi32(pcf);
  fp.x0 = _mm256_sub_epi32(bx, half);
  fp.y0 = _mm256_sub_epi32(by, half);
  const __m256i w = lane_i(c.width, face), h = lane_i(c.height, face);
  const __m256i neg1 = _mm256_set1_epi32(-1);
  // x0 >= 0, y0 >= 0, x0 + pcf < w, y0 + pcf < h.
  fp.inside = _mm256_castsi256_ps(_mm256_and_si256(
      _mm256_and_si256(_mm256_cmpgt_epi32(fp.x0, neg1), _mm256_cmpgt_epi32(fp.y0, neg1)),
      _mm256_and_si256(_mm256_cmpgt_epi32(w, _mm256_add_epi32(fp.x0, n)),
                       _mm256_cmpgt_epi32(h, _mm256_add_epi32(fp.y0, n)))));
  return fp;
}

// Mask of lanes that look nothing up: 1 uncovered, 0 otherwise.
SL_AVX2 inline __m256 base_mask(const R8& r) {
  return _mm256_blendv_ps(set(1.0f), _mm256_setzero_ps(), r.covered);
}

SL_AVX2 inline void store_texels(uint32_t* texels, const R8& r, __m256 lanes) {
  if (texels)
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(texels),
                        _mm256_blendv_epi8(_mm256_set1_epi32(-1), r.texel, _mm256_castps_si256(lanes)));
}

SL_AVX2 void receivers8_avx2(const MapLookupConsts& c, const float* pos, const float* nrm,
                             const uint8_t* covered, Receivers8& out) {
  const R8 r = receivers(c, pos, nrm, covered);
  _mm256_store_ps(out.sx, r.sx);
  _mm256_store_ps(out.sy, r.sy);
  _mm256_store_ps(out.depth, r.depth);
  _mm256_store_ps(out.mask, base_mask(r));
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.face), r.face);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.texel),
                     _mm256_blendv_epi8(_mm256_set1_epi32(-1), r.texel, _mm256_castps_si256(r.active)));
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.active), _mm256_castps_si256(r.active));
}

// dst = clamp(v, lo, hi) >> shift, per lane (texel indices to tile indices).
SL_AVX2 inline void store_tiles(int32_t* dst, __m256i v, __m256i lo, __m256i hi, __m128i shift) {
  const __m256i c = _mm256_min_epi32(_mm256_max_epi32(v, lo), hi);
  _mm256_store_si256(reinterpret_cast<__m256i*>(dst), _mm256_srl_epi32(c, shift));
}

SL_AVX2 void footprint_tiles8_avx2(const MapLookupConsts& c, const float* pos, const float* nrm,
                                   const uint8_t* covered, int tile_shift, FootprintTiles8& out) {
  const Front f = front(c, pos, nrm, covered);
  __m256 sx, sy, axial;
  texel_coords(c, f, sx, sy, axial);
  // bilinear_taps: floor(st − ½) and the next texel, each clamped to the image.
  const __m256 half = set(0.5f);
  const __m256i ix = floor_i(_mm256_sub_ps(sx, half)), iy = floor_i(_mm256_sub_ps(sy, half));
  const __m256i zero = _mm256_setzero_si256(), one = _mm256_set1_epi32(1);
  const __m256i wm = _mm256_sub_epi32(lane_i(c.width, f.face), one);
  const __m256i hm = _mm256_sub_epi32(lane_i(c.height, f.face), one);
  // Texel indices are >= 0 after the clamp: the division by the tile edge is a shift.
  const __m128i t = _mm_cvtsi32_si128(tile_shift);
  store_tiles(out.tx0, ix, zero, wm, t);
  store_tiles(out.tx1, _mm256_add_epi32(ix, one), zero, wm, t);
  store_tiles(out.ty0, iy, zero, hm, t);
  store_tiles(out.ty1, _mm256_add_epi32(iy, one), zero, hm, t);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.face), f.face);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.active), _mm256_castps_si256(f.active));
}

SL_AVX2 void depth1_avx2(const MapLookupConsts& c, const float* pos, const float* nrm,
                         const uint8_t* covered, float* mask, uint32_t* texels) {
  const R8 r = receivers(c, pos, nrm, covered);
  // The texel's stored distance, read only for active lanes (an inactive lane's face may not
  // have been rendered).
  const __m256i idx = _mm256_add_epi32(lane_i(c.offset, r.face),
                                       _mm256_sub_epi32(r.texel, lane_i(c.base, r.face)));
  const __m256 stored = _mm256_mask_i32gather_ps(_mm256_setzero_ps(), c.depth_base, idx, r.active, 4);
  const __m256 lit = _mm256_and_ps(_mm256_cmp_ps(r.depth, stored, _CMP_LE_OQ), set(1.0f));
  _mm256_storeu_ps(mask, _mm256_blendv_ps(base_mask(r), lit, r.active));
  store_texels(texels, r, r.active);
}

SL_AVX2 void pcf_avx2(const MapLookupConsts& c, int pcf, const float* pos, const float* nrm,
                      const uint8_t* covered, float* mask, uint32_t* texels, Receivers8& rest) {
  const R8 r = receivers(c, pos, nrm, covered);
  // for_each_pcf_tap's footprint: columns x0 .. x0 + pcf, weights (1 - fx, 1, …, 1, fx)/pcf
  // per axis, rows likewise, summed row by row in the scalar walk's order.
  const Footprint fp = footprint(c, pcf, r.sx, r.sy, r.face);
  const __m256 vec = _mm256_and_ps(r.active, fp.inside);
  const __m256 one = set(1.0f), zero = _mm256_setzero_ps();
  const __m256 norm = set(1.0f / float(pcf * pcf));
  const __m256i w = lane_i(c.width, r.face);
  __m256 lit = zero, total = zero;
  const __m256i origin = _mm256_add_epi32(lane_i(c.offset, r.face), fp.x0);
  for (int j = 0; j <= pcf; ++j) {
    const __m256 wy = j == 0 ? _mm256_sub_ps(one, fp.fy) : (j == pcf ? fp.fy : one);
    const __m256i row = _mm256_add_epi32(origin, _mm256_mullo_epi32(_mm256_add_epi32(fp.y0, _mm256_set1_epi32(j)), w));
    for (int i = 0; i <= pcf; ++i) {
      const __m256 wx = i == 0 ? _mm256_sub_ps(one, fp.fx) : (i == pcf ? fp.fx : one);
      const __m256 wt = _mm256_mul_ps(_mm256_mul_ps(wx, wy), norm);
      const __m256 tap = _mm256_mask_i32gather_ps(zero, c.depth_base,
                                                  _mm256_add_epi32(row, _mm256_set1_epi32(i)), vec, 4);
      total = _mm256_add_ps(total, wt);
      lit = _mm256_add_ps(lit, _mm256_and_ps(_mm256_cmp_ps(r.depth, tap, _CMP_LE_OQ), wt));
    }
  }
  const __m256 vis = _mm256_blendv_ps(one, _mm256_min_ps(_mm256_div_ps(lit, total), one),
                                      _mm256_cmp_ps(total, zero, _CMP_GT_OQ));
  // std::clamp(vis, 0, 1) of the pixel loop: vis is already in [0, 1].
  _mm256_storeu_ps(mask, _mm256_blendv_ps(base_mask(r), vis, vec));
  store_texels(texels, r, r.active);
  // The active lanes the vector loop did not take go to the scalar tap walk.
  const __m256 left = _mm256_andnot_ps(vec, r.active);
  _mm256_store_ps(rest.sx, r.sx);
  _mm256_store_ps(rest.sy, r.sy);
  _mm256_store_ps(rest.depth, r.depth);
  _mm256_store_si256(reinterpret_cast<__m256i*>(rest.face), r.face);
  _mm256_store_si256(reinterpret_cast<__m256i*>(rest.texel), r.texel);
  _mm256_store_si256(reinterpret_cast<__m256i*>(rest.active), _mm256_castps_si256(left));
}

SL_AVX2 Faces8 faces8_avx2(const MapLookupConsts& c, int cross_pcf, const float* pos,
                           const float* nrm, const uint8_t* covered, Receivers8& rest) {
  const Front f = front(c, pos, nrm, covered);
  Faces8 out;
  const int active_bits = _mm256_movemask_ps(f.active);
  out.looked_up = uint32_t(__builtin_popcount(unsigned(active_bits)));
  // OR of 1 << face over the active lanes.
  const __m256i bit = _mm256_and_si256(_mm256_sllv_epi32(_mm256_set1_epi32(1), f.face),
                                       _mm256_castps_si256(f.active));
  __m128i o = _mm_or_si128(_mm256_castsi256_si128(bit), _mm256_extracti128_si256(bit, 1));
  o = _mm_or_si128(o, _mm_shuffle_epi32(o, 0x4E));
  o = _mm_or_si128(o, _mm_shuffle_epi32(o, 0xB1));
  out.bits = uint32_t(_mm_cvtsi128_si32(o));
  out.rest = false;
  if (cross_pcf > 1 && active_bits) {
    __m256 sx, sy, axial;
    texel_coords(c, f, sx, sy, axial);
    const Footprint fp = footprint(c, cross_pcf, sx, sy, f.face);
    const __m256 left = _mm256_andnot_ps(fp.inside, f.active);
    if (_mm256_movemask_ps(left)) {
      out.rest = true;
      _mm256_store_ps(rest.sx, sx);
      _mm256_store_ps(rest.sy, sy);
      _mm256_store_si256(reinterpret_cast<__m256i*>(rest.face), f.face);
      _mm256_store_si256(reinterpret_cast<__m256i*>(rest.active), _mm256_castps_si256(left));
    }
  }
  return out;
}

SL_AVX2 inline __m256i clamp_i(__m256i v, __m256i lo, __m256i hi) {
  return _mm256_min_epi32(_mm256_max_epi32(v, lo), hi);
}

SL_AVX2 void bilinear8_avx2(const MapLookupConsts& c, const Receivers8& r,
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

// bilinear8_avx2 with plain loads instead of gathers: each lane's two taps of a row, (x0, y)
// and (x0 + 1, y), are adjacent floats, so one 8-byte load fetches both (half the element
// loads of the gathers, and no gather microcode, which costs most of the filters' lookups on
// the AMD parts we measure on: README "Technique benchmark"). The pair starts at
// clamp(ix, 0, w − 2), inside the row; a lane clamped at the left edge takes the pair's first
// value for both taps, one at the right edge its second, so the taps are bilinear_taps' clamped
// texels as before, bit for bit. Inactive lanes load texel 0 of face 0's plane and are zeroed,
// as the masked gathers leave them. Needs every face at least 2 texels wide (the dispatcher
// below checks).
SL_AVX2 void bilinear8_pairs_avx2(const MapLookupConsts& c, const Receivers8& r,
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
    bilinear8_avx2(c, r, planes, n, values, fx, fy);
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
SL_AVX2 inline __m256i fill_inactive(__m256i v, __m256i active, int active_bits) {
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
SL_AVX2 inline bool pair_rows(const MapLookupConsts& c, const Receivers8& r, const PlaneGather& plane,
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
SL_AVX2 inline void store_pair(const PairRows& p, __m256 first, __m256 second, float (*tap)[8], int y) {
  _mm256_storeu_ps(tap[2 * y], _mm256_and_ps(_mm256_blendv_ps(first, second, p.right), p.active));
  _mm256_storeu_ps(tap[2 * y + 1], _mm256_and_ps(_mm256_blendv_ps(second, first, p.left), p.active));
}

// The bilinear footprint of 8 receivers in one interleaved plane of two values per texel
// (variance_map.cpp's mean and variance, EVSM2's): one 16-byte load per lane and tap row fetches
// both taps' two values, then a 4 × 4 transpose in each half. values[v][tap][lane].
SL_AVX2 void bilinear8_interleaved2_avx2(const MapLookupConsts& c, const Receivers8& r,
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
SL_AVX2 void bilinear8_interleaved4_avx2(const MapLookupConsts& c, const Receivers8& r,
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
// rows and no round trip of the 16 tap vectors through memory (bilinear8_interleaved4_avx2 and
// the batch's reload); then a 4 × 4 transpose per half. Inactive lanes get zeros.
SL_AVX2 void bilinear8_mix4_avx2(const MapLookupConsts& c, const Receivers8& r,
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

SL_AVX2 void prefetch8_avx2(const MapLookupConsts& c, const Receivers8& r,
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

}  // namespace
#endif

#ifdef SHADOWLAB_HAVE_X86
SL_AVX2 void merge8(const Receivers8& r, const float* vis, float* mask, uint32_t* texels) {
  const __m256 v = _mm256_load_ps(vis), zero = _mm256_setzero_ps(), one = set(1.0f);
  // std::clamp(v, 0, 1): v < 0 ? 0 : (1 < v ? 1 : v).
  const __m256 c = _mm256_blendv_ps(_mm256_blendv_ps(v, one, _mm256_cmp_ps(one, v, _CMP_LT_OQ)),
                                    zero, _mm256_cmp_ps(v, zero, _CMP_LT_OQ));
  const __m256 active = _mm256_castsi256_ps(_mm256_load_si256(reinterpret_cast<const __m256i*>(r.active)));
  _mm256_storeu_ps(mask, _mm256_blendv_ps(_mm256_load_ps(r.mask), c, active));
  if (texels)
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(texels),
                        _mm256_load_si256(reinterpret_cast<const __m256i*>(r.texel)));
}
#else
void merge8(const Receivers8& r, const float* vis, float* mask, uint32_t* texels) {
  for (int k = 0; k < 8; ++k) {
    mask[k] = r.active[k] ? std::clamp(vis[k], 0.0f, 1.0f) : r.mask[k];
    if (texels) texels[k] = uint32_t(r.texel[k]);
  }
}
#endif

Prefetch8Fn prefetch8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return prefetch8_avx2;
#endif
  return nullptr;
}

Bilinear8x2Fn bilinear8_interleaved4_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return bilinear8_interleaved4_avx2;
#endif
  return nullptr;
}

Mix8x4Fn bilinear8_mix4_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return bilinear8_mix4_avx2;
#endif
  return nullptr;
}

Bilinear8x2Fn bilinear8_interleaved2_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return bilinear8_interleaved2_avx2;
#endif
  return nullptr;
}

Receivers8Fn receivers8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return receivers8_avx2;
#endif
  return nullptr;
}

FootprintTiles8Fn footprint_tiles8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return footprint_tiles8_avx2;
#endif
  return nullptr;
}

Depth1Fn depth1_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return depth1_avx2;
#endif
  return nullptr;
}

Faces8Fn faces8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return faces8_avx2;
#endif
  return nullptr;
}

Bilinear8Fn bilinear8_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return bilinear8_pairs_avx2;
#endif
  return nullptr;
}

PcfFn pcf_simd() {
#ifdef SHADOWLAB_HAVE_X86
  if (use_avx2_paths()) return pcf_avx2;
#endif
  return nullptr;
}

}  // namespace shadowlab

// File-local: a unity build compiles the next file in the same translation unit.
#undef SL_AVX2
#undef SHADOWLAB_HAVE_X86
