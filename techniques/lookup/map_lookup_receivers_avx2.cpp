// The AVX2 receivers of the lookup (techniques/lookup/map_lookup_simd.h): make_receiver() and
// lookup_faces()' gates for 8 pixels, and the kernels built on them (the one-tap and N×N
// compares, the faces needed, the footprints' tiles, the merge into the mask). Compiled with
// -mavx2 -mfma (docs/simd.md).
#if defined(__x86_64__)
#include "techniques/lookup/map_lookup_lanes_avx2.h"

namespace shadowlab::lookup_avx2 {

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

inline Front front(const MapLookupConsts& c, const float* pos, const float* nrm,
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
inline void texel_coords(const MapLookupConsts& c, const Front& f, __m256& sx, __m256& sy,
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
inline R8 receivers(const MapLookupConsts& c, const float* pos, const float* nrm,
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
inline Footprint footprint(const MapLookupConsts& c, int pcf, __m256 sx, __m256 sy, __m256i face) {
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
inline __m256 base_mask(const R8& r) {
  return _mm256_blendv_ps(set(1.0f), _mm256_setzero_ps(), r.covered);
}

inline void store_texels(uint32_t* texels, const R8& r, __m256 lanes) {
  if (texels)
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(texels),
                        _mm256_blendv_epi8(_mm256_set1_epi32(-1), r.texel, _mm256_castps_si256(lanes)));
}

void receivers8(const MapLookupConsts& c, const float* pos, const float* nrm,
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
inline void store_tiles(int32_t* dst, __m256i v, __m256i lo, __m256i hi, __m128i shift) {
  const __m256i c = _mm256_min_epi32(_mm256_max_epi32(v, lo), hi);
  _mm256_store_si256(reinterpret_cast<__m256i*>(dst), _mm256_srl_epi32(c, shift));
}

void footprint_tiles8(const MapLookupConsts& c, const float* pos, const float* nrm,
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

void depth1(const MapLookupConsts& c, const float* pos, const float* nrm,
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

void pcf(const MapLookupConsts& c, int pcf, const float* pos, const float* nrm,
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

Faces8 faces8(const MapLookupConsts& c, int cross_pcf, const float* pos,
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

void merge8(const Receivers8& r, const float* vis, float* mask, uint32_t* texels) {
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

}  // namespace shadowlab::lookup_avx2
#endif
