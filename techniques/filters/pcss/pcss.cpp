// Percentage-closer soft shadows ("pcss": cpcss, tpcss, ppcss; Fernando 2005) on the stored
// radial distances: per pixel, (1) a blocker search over a rotated Poisson disk whose width
// follows from the light's size and the receiver's distance, (2) the mean distance of the
// blockers found, (3) the penumbra width (d_receiver − d_blocker)/d_blocker × light radius,
// (4) rotated Poisson PCF over that width. Every rotation comes from the pixel's counter-based
// random number (core/rng.h), never the thread. docs/techniques/pcss.md gives the geometry.
#include <algorithm>
#include <cmath>
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <fmt/format.h>

#include "core/error.h"
#include "core/simd_target.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"
#include "techniques/filters/pcss/penumbra_model.h"
#include "techniques/lookup/poisson_disk.h"
#include "techniques/lookup/tap_avx2.h"

namespace shadowlab {
// The filter's own namespace: the unity build compiles several filters in one translation
// unit, and each defines the same MapFilterOps entries (keys, lookup, ...).
namespace pcss_filter {
namespace {

const std::vector<MapKey>& keys() {
  static const std::vector<MapKey> k = {
      {.name = "light_size", .type = KeyType::Number, .def = -1.0, .def_word = "light", .lo = 0.0,
       .hi = 100.0, .word = "light",
       .help = "light radius, m; light: the scene light's radius, known only at lookup",
       .store = [](MapParams& p, const KeyValue& v) { p.pcss.light_size = v.number; }},
      {.name = "search", .type = KeyType::Integer, .def = 16, .lo = 1, .hi = 256,
       .help = "blocker-search taps (rotated Poisson disk)",
       .store = [](MapParams& p, const KeyValue& v) { p.pcss.search = int(v.number); }},
      {.name = "taps", .type = KeyType::Integer, .def = 32, .lo = 1, .hi = 256,
       .help = "PCF taps (rotated Poisson disk)",
       .store = [](MapParams& p, const KeyValue& v) { p.pcss.taps = int(v.number); }},
      {.name = "search_near", .type = KeyType::Number, .def = 0.25, .lo = 0.01, .hi = 0.99,
       .help = "nearest blocker searched for, as a fraction of the receiver's distance (sets "
               "the search disk)",
       .store = [](MapParams& p, const KeyValue& v) { p.pcss.search_near = v.number; }},
      {.name = "estimate", .type = KeyType::Choice, .def_word = "classic", .choices = "classic|model",
       .help = "the penumbra width: classic (the mean blocker ratio) or model (the blockers' "
               "depth range, techniques/filters/pcss/penumbra_model.h)",
       .store = [](MapParams& p, const KeyValue& v) { p.pcss.model = v.word == "model"; }},
      [] { MapKey r = map_rpdb_key(); r.def = 1; return r; }(),
  };
  return k;
}

void filter(const MapParams&, LightMap&) {}  // the stored distances are the map

struct PcssContext {
  const FaceLayout& layout;
  const std::vector<LineAlignedFloats>& dist;
  PoissonDisk search, taps;
  double radius;       // light radius / far (normalised distance units)
  double search_near;  // nearest blocker searched for, × the receiver's distance
  bool model;          // estimate=model (pcss_model_radius)
};

// The face and continuous coordinates of taps at st of `face`: st itself inside the face's
// image, else the tap's direction looked up in the face that owns it (the projector's one face:
// clamped to its image).
inline void tap_face(const FaceLayout& L, int face, vec2 st, int& f_out, vec2& st_out) {
  const LightFace& f = L.faces[size_t(face)];
  if (st.x >= 1.0f && st.y >= 1.0f && st.x <= float(f.width) - 1.0f &&
      st.y <= float(f.height) - 1.0f) {
    f_out = face;
    st_out = st;
    return;
  }
  const vec3 dir = face_texel_direction(f, st.x, st.y);
  f_out = face_of(L, dir);
  const LightFace& g = L.faces[size_t(f_out)];
  st_out = glm::dot(dir, g.forward) > 0.0f ? face_texel_coords(g, dir) : st;
}

// Stored distance of the texel under st (nearest texel).
inline float depth_at(const PcssContext& c, int face, vec2 st) {
  int f;
  vec2 s;
  tap_face(c.layout, face, st, f, s);
  const LightFace& lf = c.layout.faces[size_t(f)];
  return c.dist[size_t(f)][size_t(clamp_texel(s.y, lf.height)) * size_t(lf.width) +
                           size_t(clamp_texel(s.x, lf.width))];
}

// Lit fraction of a bilinear-weighted compare at st for receiver r: each texel compared with
// the receiver's depth, moved along rpdb's plane to the texel's centre (grad is 0 without rpdb;
// a tap read in another face keeps the plane's depth at the tap).
inline float compare_at(const PcssContext& c, const Receiver& r, vec2 st) {
  int f;
  vec2 s;
  tap_face(c.layout, r.face, st, f, s);
  const LightFace& lf = c.layout.faces[size_t(f)];
  const Bilinear b = bilinear_taps(s, lf.width, lf.height);
  const float* d = c.dist[size_t(f)].data();
  const bool own = f == r.face;
  const float tap_depth = r.depth + glm::dot(r.grad, st - r.st);
  auto at = [&](int x, int y) {
    const float depth =
        own ? r.depth + glm::dot(r.grad, vec2(float(x) + 0.5f, float(y) + 0.5f) - r.st) : tap_depth;
    return depth <= d[size_t(y) * size_t(lf.width) + size_t(x)] ? 1.0f : 0.0f;
  };
  return (1.0f - b.fy) * ((1.0f - b.fx) * at(b.x0, b.y0) + b.fx * at(b.x1, b.y0)) +
         b.fy * ((1.0f - b.fx) * at(b.x0, b.y1) + b.fx * at(b.x1, b.y1));
}

// Per-receiver quantities of the four stages. Angles (radians, seen from the light) become
// texels by the face's texels per plane unit × ρ, ρ = √(1 + u² + v²) the distance from the light
// to the receiver's point on the unit image plane (the isotropic, tangential scale of the
// gnomonic map; radially it stretches by another ρ, ignored).
struct PcssLane {
  double t;                 // the receiver's depth
  float texels_per_radian;
  float max_radius;         // half a face
  float search_radius;      // texels
  vec2 rot_s, rot;          // the search disk's and the PCF disk's rotations
};

PcssLane pcss_lane(const PcssContext& c, const Receiver& r) {
  const LightFace& f = c.layout.faces[size_t(r.face)];
  PcssLane l;
  const float per_plane = float(f.width) / (f.right_edge - f.left);  // texels per plane unit
  const float u = f.left + r.st.x / per_plane;
  const float v = f.top - r.st.y * (f.top - f.bottom) / float(f.height);
  // (The paraboloid map is conformal, with 2/(1 + u² + v²) radians per plane unit.)
  l.texels_per_radian = f.paraboloid ? per_plane * 0.5f * (1.0f + u * u + v * v)
                                     : per_plane * std::sqrt(1.0f + u * u + v * v);
  l.t = double(r.depth);
  l.max_radius = 0.5f * float(std::max(f.width, f.height));
  // 1. Blocker search: blockers at s·t or farther can hide part of the light from the receiver
  //    only within the angle R·(t − s·t)/(s·t·t) of its direction.
  const double s = c.search_near;
  l.search_radius = std::clamp(float(c.radius * (1.0 - s) / (s * l.t)) * l.texels_per_radian,
                               1.0f, l.max_radius);
  l.rot_s = poisson_rotation(r.pixel ^ (size_t(1) << 62));
  l.rot = poisson_rotation(r.pixel);
  return l;
}

// 2–3. Mean blocker distance and the penumbra's angular radius R·(t − t_b)/(t_b·t), in texels.
float pcss_radius(const PcssContext& c, const PcssLane& l, double blocker_sum, int blockers) {
  const double tb = blocker_sum / double(blockers);
  const float r = float(c.radius * (l.t - tb) / (tb * l.t)) * l.texels_per_radian;
  // 0/0 (no light size and every blocker at distance 0, e.g. 8-bit depth near the light): the
  // smallest radius, not a NaN tap position.
  return r == r ? std::clamp(r, 1.0f, l.max_radius) : 1.0f;
}

// estimate=model: the penumbra-width model (techniques/filters/pcss/penumbra_model.h) with the emitter of
// radius R at the light, the receiver at depth t and the occluders between the nearest and the
// farthest blocker found (as its sphere): the PCF radius is half its width w (the kernel centred
// on the edge spans the whole transition, as the classic radius does: w → 2·R·(t − z_m)/z_m for
// a thin occluder), as an angle w/(2t), in texels.
float pcss_model_radius(const PcssContext& c, const PcssLane& l, double z_min, double z_max) {
  const PenumbraModel m = penumbra_model(c.radius, l.t, z_min, z_max);
  const float r = float(0.5 * m.width / l.t) * l.texels_per_radian;
  return r == r ? std::clamp(r, 1.0f, l.max_radius) : 1.0f;  // as pcss_radius
}

// The four stages for one receiver (the scalar oracle of the batch below).
float pcss_visibility(const PcssContext& c, const Receiver& r) {
  const PcssLane l = pcss_lane(c, r);
  double blocker_sum = 0.0, z_min = 1e300, z_max = 0.0;
  int blockers = 0;
  for (const vec2& q : c.search.points) {
    const vec2 st(r.st.x + l.search_radius * (l.rot_s.x * q.x - l.rot_s.y * q.y),
                  r.st.y + l.search_radius * (l.rot_s.y * q.x + l.rot_s.x * q.y));
    const float z = depth_at(c, r.face, st);
    if (z < r.depth + glm::dot(r.grad, st - r.st)) {  // grad: rpdb's plane (else 0)
      blocker_sum += double(z);
      z_min = std::min(z_min, double(z));
      z_max = std::max(z_max, double(z));
      ++blockers;
    }
  }
  if (blockers == 0) return 1.0f;
  const float radius = c.model ? pcss_model_radius(c, l, z_min, z_max)
                               : pcss_radius(c, l, blocker_sum, blockers);
  // 4. Rotated Poisson PCF over that radius.
  float lit = 0.0f;
  for (const vec2& q : c.taps.points) {
    const vec2 st(r.st.x + radius * (l.rot.x * q.x - l.rot.y * q.y),
                  r.st.y + radius * (l.rot.y * q.x + l.rot.x * q.y));
    lit += compare_at(c, r, st);
  }
  return lit / float(c.taps.points.size());
}

#if defined(__x86_64__)
#define SL_AVX2 SL_TARGET("avx2")
// Lanes whose tap (x, y) lies outside [1, w − 1] × [1, h − 1], where tap_face would look it up in
// another face (those lanes take the scalar stages).
SL_AVX2 inline __m256 pcss_outside(__m256 x, __m256 y, __m256 wm1, __m256 hm1) {
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 in = _mm256_and_ps(
      _mm256_and_ps(_mm256_cmp_ps(x, one, _CMP_GE_OQ), _mm256_cmp_ps(y, one, _CMP_GE_OQ)),
      _mm256_and_ps(_mm256_cmp_ps(x, wm1, _CMP_LE_OQ), _mm256_cmp_ps(y, hm1, _CMP_LE_OQ)));
  return _mm256_xor_ps(in, _mm256_castsi256_ps(_mm256_set1_epi32(-1)));
}

// The stages for the 8 lanes of a batch whose taps stay in their face's image, in the scalar
// code's operations and order: `lanes` are the per-lane quantities, gx/gy the plane gradients.
// Returns the lanes left to the scalar code (a tap outside the image, or stage 4 skipped:
// no blocker) in `rest`, and the others' visibility in out.
SL_AVX2 void pcss_batch_avx2(const MapLookupConsts& mc, const PcssContext& c, const Receivers8& r,
                             const PcssLane* lanes, const float* gxv, const float* gyv,
                             const int* active, float* out, bool* rest) {
  alignas(32) float rs[8], cs_s[8], sn_s[8], cs[8], sn[8];
  for (int k = 0; k < 8; ++k) {
    rs[k] = lanes[k].search_radius;
    cs_s[k] = lanes[k].rot_s.x;
    sn_s[k] = lanes[k].rot_s.y;
    cs[k] = lanes[k].rot.x;
    sn[k] = lanes[k].rot.y;
  }
  const __m256i zero_i = _mm256_setzero_si256();
  const __m256i act = _mm256_setr_epi32(active[0], active[1], active[2], active[3], active[4],
                                        active[5], active[6], active[7]);
  __m256 live = _mm256_castsi256_ps(_mm256_xor_si256(_mm256_cmpeq_epi32(act, zero_i),
                                                     _mm256_set1_epi32(-1)));
  const __m256i face = _mm256_and_si256(_mm256_load_si256(reinterpret_cast<const __m256i*>(r.face)),
                                        _mm256_castps_si256(live));
  const __m256i width = face_lanes(mc.width, face), height = face_lanes(mc.height, face);
  const __m256i offset = face_lanes(mc.offset, face);
  const __m256 wm1 = _mm256_sub_ps(_mm256_cvtepi32_ps(width), _mm256_set1_ps(1.0f));
  const __m256 hm1 = _mm256_sub_ps(_mm256_cvtepi32_ps(height), _mm256_set1_ps(1.0f));
  const __m256 sx = _mm256_load_ps(r.sx), sy = _mm256_load_ps(r.sy);
  const __m256 depth = _mm256_load_ps(r.depth);
  const __m256 gx = _mm256_loadu_ps(gxv), gy = _mm256_loadu_ps(gyv);
  // 1. Blocker search.
  __m256 outside = _mm256_setzero_ps();
  __m256d sum_lo = _mm256_setzero_pd(), sum_hi = _mm256_setzero_pd();
  __m256i count = zero_i;
  {
    const __m256 rad = _mm256_load_ps(rs), c0 = _mm256_load_ps(cs_s), s0 = _mm256_load_ps(sn_s);
    for (const vec2& q : c.search.points) {
      __m256 tx, ty;
      rotated_tap(sx, sy, rad, c0, s0, q, tx, ty);
      outside = _mm256_or_ps(outside, pcss_outside(tx, ty, wm1, hm1));
      const __m256 ok = _mm256_andnot_ps(outside, live);
      // Nearest texel: inside the image st >= 1, so truncation is clamp_texel's floor.
      const __m256i ix = _mm256_cvttps_epi32(tx), iy = _mm256_cvttps_epi32(ty);
      const __m256 z = stored_distance(mc, offset, width, ix, iy, ok);
      const __m256 thr = _mm256_add_ps(depth, _mm256_add_ps(_mm256_mul_ps(gx, _mm256_sub_ps(tx, sx)),
                                                            _mm256_mul_ps(gy, _mm256_sub_ps(ty, sy))));
      const __m256 blocker = _mm256_and_ps(_mm256_cmp_ps(z, thr, _CMP_LT_OQ), ok);
      const __m256 zb = _mm256_and_ps(z, blocker);  // +0 where not a blocker
      sum_lo = _mm256_add_pd(sum_lo, _mm256_cvtps_pd(_mm256_castps256_ps128(zb)));
      sum_hi = _mm256_add_pd(sum_hi, _mm256_cvtps_pd(_mm256_extractf128_ps(zb, 1)));
      count = _mm256_sub_epi32(count, _mm256_castps_si256(blocker));
    }
  }
  alignas(32) double sums[8];
  alignas(32) int32_t counts[8];
  alignas(32) float out_mask[8];
  _mm256_store_pd(sums, sum_lo);
  _mm256_store_pd(sums + 4, sum_hi);
  _mm256_store_si256(reinterpret_cast<__m256i*>(counts), count);
  _mm256_store_ps(out_mask, outside);
  // 2–3 per lane; lanes with a tap outside, or none active, leave the batch.
  alignas(32) float radius[8];
  for (int k = 0; k < 8; ++k) {
    radius[k] = 0.0f;
    rest[k] = active[k] && out_mask[k] != 0.0f;
    if (!active[k] || rest[k]) continue;
    if (counts[k] == 0) {
      out[k] = 1.0f;
      continue;
    }
    radius[k] = pcss_radius(c, lanes[k], sums[k], counts[k]);
  }
  alignas(32) int32_t pcf_lanes[8];  // lanes that go on to stage 4 here
  for (int k = 0; k < 8; ++k) pcf_lanes[k] = active[k] && !rest[k] && counts[k] > 0 ? -1 : 0;
  live = _mm256_castsi256_ps(_mm256_load_si256(reinterpret_cast<const __m256i*>(pcf_lanes)));
  if (_mm256_movemask_ps(live) == 0) return;
  // 4. Rotated Poisson PCF over each lane's radius.
  const __m256 rad = _mm256_load_ps(radius), c1 = _mm256_load_ps(cs), s1 = _mm256_load_ps(sn);
  const __m256 one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
  const __m256i one_i = _mm256_set1_epi32(1);
  __m256 outside4 = _mm256_setzero_ps();
  __m256 lit = _mm256_setzero_ps();
  for (const vec2& q : c.taps.points) {
    __m256 tx, ty;
    rotated_tap(sx, sy, rad, c1, s1, q, tx, ty);
    outside4 = _mm256_or_ps(outside4, pcss_outside(tx, ty, wm1, hm1));
    const __m256 ok = _mm256_andnot_ps(outside4, live);
    // bilinear_taps inside the image: floor is truncation, no clamping.
    const __m256 bx = _mm256_sub_ps(tx, half), by = _mm256_sub_ps(ty, half);
    const __m256i x0 = _mm256_cvttps_epi32(bx), y0 = _mm256_cvttps_epi32(by);
    const __m256 fx = _mm256_sub_ps(bx, _mm256_cvtepi32_ps(x0));
    const __m256 fy = _mm256_sub_ps(by, _mm256_cvtepi32_ps(y0));
    const __m256i x1 = _mm256_add_epi32(x0, one_i), y1 = _mm256_add_epi32(y0, one_i);
    __m256 a[4];
    const __m256i xs[4] = {x0, x1, x0, x1}, ys[4] = {y0, y0, y1, y1};
    for (int i = 0; i < 4; ++i) {
      const __m256 d = stored_distance(mc, offset, width, xs[i], ys[i], ok);
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
  alignas(32) float res[8], out4[8], live_f[8];
  _mm256_store_ps(res, _mm256_div_ps(lit, _mm256_set1_ps(float(c.taps.points.size()))));
  _mm256_store_ps(out4, outside4);
  _mm256_store_ps(live_f, live);
  for (int k = 0; k < 8; ++k) {
    if (live_f[k] == 0.0f) continue;
    if (out4[k] != 0.0f)
      rest[k] = true;
    else
      out[k] = res[k];
  }
}
#undef SL_AVX2
#endif

// 8 lanes at once: each lane's receiver-plane gradient as make_receiver computes it (from the
// GBuffer's position and geometric normal; the AVX2 receivers carry none), its per-lane
// quantities (pcss_lane), then pcss_batch_avx2; lanes with a tap outside their face's image
// take pcss_visibility whole.
struct PcssBatch {
  static constexpr bool kEnabled = true;
  void prefetch(const MapLookupConsts&, const Receivers8&) const {}  // taps spread over a disk
  static constexpr bool kComputesGradient = true;
  const PcssContext* ctx;
  const Scene* scene;
  const GBuffer* g;
  bool rpdb;
  void operator()(const MapLookupConsts& mc, const Receivers8& r, size_t first, float* out) const {
    Receiver rc[8];
    PcssLane lanes[8];
    float gxv[8], gyv[8];
    int active[8];
    const float inv_far = 1.0f / scene->light.far;
    for (int k = 0; k < 8; ++k) {
      active[k] = r.active[k] != 0;
      gxv[k] = gyv[k] = 0.0f;
      if (!active[k]) {
        lanes[k] = PcssLane{1.0, 0.0f, 0.0f, 1.0f, vec2(1.0f, 0.0f), vec2(1.0f, 0.0f)};
        continue;
      }
      const size_t i = first + size_t(k);
      rc[k] = lane_receiver(r, k, i);
      if (rpdb) {
        const LightFace& f = ctx->layout.faces[size_t(rc[k].face)];
        const vec3 to_p = g->position[i] - scene->light.position;
        rc[k].grad = f.paraboloid
                         ? receiver_plane_gradient_numeric(f, rc[k].st, to_p, g->geo_normal[i], inv_far)
                         : receiver_plane_gradient(f, to_p, g->geo_normal[i], inv_far);
      }
      gxv[k] = rc[k].grad.x;
      gyv[k] = rc[k].grad.y;
      lanes[k] = pcss_lane(*ctx, rc[k]);
    }
    bool rest[8] = {};
#if defined(__x86_64__)
    if (mc.gather_ok)
      pcss_batch_avx2(mc, *ctx, r, lanes, gxv, gyv, active, out, rest);
    else
      for (int k = 0; k < 8; ++k) rest[k] = active[k];
#endif
    for (int k = 0; k < 8; ++k)
      if (rest[k]) out[k] = pcss_visibility(*ctx, rc[k]);
  }
};

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const double light = p.pcss.light_size < 0.0 ? double(scene.light.radius) : p.pcss.light_size;
  const PcssContext c{map.layout,
                      map.dist.distance,
                      poisson_disk(p.pcss.search),
                      poisson_disk(p.pcss.taps),
                      light / double(scene.light.far),
                      p.pcss.search_near,
                      p.pcss.model};
  auto visibility = [&](const Receiver& r) { return pcss_visibility(c, r); };
  // The model estimate runs in the scalar stages only (the AVX2 batch forms the classic one).
  if (lookup_kernels(process_isa()).receivers8 && !p.pcss.model)
    lookup_pixels(scene, g, p, map, mask, texels, visibility, PcssBatch{&c, &scene, &g, p.rpdb});
  else
    lookup_pixels(scene, g, p, map, mask, texels, visibility);
}

// Search taps read 1 texel, PCF taps 2×2.
uint64_t taps_per_lookup(const MapParams& p) {
  return uint64_t(p.pcss.search) + 4 * uint64_t(p.pcss.taps);
}
uint64_t tap_bytes(const MapParams&) { return 4; }
uint64_t stored_planes(const MapParams&) { return 0; }

}  // namespace
}  // namespace pcss_filter

const MapFilterOps kPcss = {
    "pcss", "percentage-closer soft shadows (blocker search + Poisson PCF)", MapFilter::Pcss,
    pcss_filter::keys, pcss_filter::filter, pcss_filter::lookup,
    pcss_filter::taps_per_lookup, pcss_filter::tap_bytes, pcss_filter::stored_planes, nullptr, false};

}  // namespace shadowlab
