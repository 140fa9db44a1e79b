// Percentage-closer soft shadows ("pcss": cpcss, tpcss, ppcss; Fernando 2005) on the stored
// radial distances: per pixel, (1) a blocker search over a rotated Poisson disk whose width
// follows from the light's size and the receiver's distance, (2) the mean distance of the
// blockers found, (3) the penumbra width (d_receiver − d_blocker)/d_blocker × light radius,
// (4) rotated Poisson PCF over that width. Every rotation comes from the pixel's counter-based
// random number (core/rng.h), never the thread. docs/techniques/pcss.md gives the geometry.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "techniques/lookup/lookup_batches.h"
#include "techniques/pipeline/map_filter.h"
#include "techniques/lookup/map_lookup.h"
#include "techniques/filters/pcss/penumbra_model.h"
#include "techniques/filters/pcss/pcss_scale.h"
#include "techniques/lookup/poisson_disk.h"

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
// texels by pcss_texels_per_radian (pcss_scale.h).
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
  l.texels_per_radian = pcss_texels_per_radian(f, r.st);
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

// The stages for the 8 lanes of a batch whose taps stay in their face's image, in the scalar
// code's operations and order: the blocker search and the PCF by the lookup batch table
// (techniques/lookup/lookup_batches.h), the radius per lane here. `lanes` are the per-lane quantities,
// gx/gy the plane gradients. Returns the lanes left to the scalar code (a tap outside the image,
// or stage 4 skipped: no blocker) in `rest`, and the others' visibility in out.
void pcss_batch(const LookupBatchKernels& kb, const MapLookupConsts& mc, const PcssContext& c,
                const Receivers8& r, const PcssLane* lanes, const float* gxv, const float* gyv,
                const int32_t* active, float* out, bool* rest) {
  float rs[8], cs_s[8], sn_s[8], cs[8], sn[8];
  for (int k = 0; k < 8; ++k) {
    rs[k] = lanes[k].search_radius;
    cs_s[k] = lanes[k].rot_s.x;
    sn_s[k] = lanes[k].rot_s.y;
    cs[k] = lanes[k].rot.x;
    sn[k] = lanes[k].rot.y;
  }
  // 1. Blocker search.
  double sums[8];
  int32_t counts[8];
  float outside[8];
  kb.pcss_search(mc, r, rs, cs_s, sn_s, gxv, gyv, active, c.search.points.data(),
                 int(c.search.points.size()), sums, counts, outside);
  // 2–3 per lane; lanes with a tap outside, or none active, leave the batch.
  float radius[8];
  for (int k = 0; k < 8; ++k) {
    radius[k] = 0.0f;
    rest[k] = active[k] && outside[k] != 0.0f;
    if (!active[k] || rest[k]) continue;
    if (counts[k] == 0) {
      out[k] = 1.0f;
      continue;
    }
    radius[k] = pcss_radius(c, lanes[k], sums[k], counts[k]);
  }
  int32_t pcf_lanes[8];  // lanes that go on to stage 4 here
  bool any = false;
  for (int k = 0; k < 8; ++k) {
    pcf_lanes[k] = active[k] && !rest[k] && counts[k] > 0 ? -1 : 0;
    any |= pcf_lanes[k] != 0;
  }
  if (!any) return;
  // 4. Rotated Poisson PCF over each lane's radius.
  float vis[8], outside4[8];
  kb.pcss_pcf(mc, r, radius, cs, sn, gxv, gyv, active, pcf_lanes, c.taps.points.data(),
              int(c.taps.points.size()), vis, outside4);
  for (int k = 0; k < 8; ++k) {
    if (pcf_lanes[k] == 0) continue;
    if (outside4[k] != 0.0f)
      rest[k] = true;
    else
      out[k] = vis[k];
  }
}

// 8 lanes at once: each lane's receiver-plane gradient as make_receiver computes it (from the
// GBuffer's position and geometric normal; the AVX2 receivers carry none), its per-lane
// quantities (pcss_lane), then pcss_batch; lanes with a tap outside their face's image take
// pcss_visibility whole.
struct PcssBatch {
  static constexpr bool kEnabled = true;
  void prefetch(const MapLookupConsts&, const Receivers8&) const {}  // taps spread over a disk
  static constexpr bool kComputesGradient = true;
  const PcssContext* ctx;
  const Scene* scene;
  const GBuffer* g;
  bool rpdb;
  const LookupBatchKernels* kb;
  void operator()(const MapLookupConsts& mc, const Receivers8& r, size_t first, float* out) const {
    Receiver rc[8];
    PcssLane lanes[8];
    float gxv[8], gyv[8];
    int32_t active[8];
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
    if (mc.gather_ok)
      pcss_batch(*kb, mc, *ctx, r, lanes, gxv, gyv, active, out, rest);
    else
      for (int k = 0; k < 8; ++k) rest[k] = active[k];
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
  const LookupBatchKernels& kb = lookup_batch_kernels(process_isa());
  if (lookup_kernels(process_isa()).receivers8 && kb.pcss_search && !p.pcss.model)
    lookup_pixels(scene, g, p, map, mask, texels, visibility,
                  PcssBatch{&c, &scene, &g, p.rpdb, &kb});
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
