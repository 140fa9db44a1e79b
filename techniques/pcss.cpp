// Percentage-closer soft shadows ("pcss": cpcss, tpcss, ppcss; Fernando 2005) on the stored
// radial distances: per pixel, (1) a blocker search over a rotated Poisson disk whose width
// follows from the light's size and the receiver's distance, (2) the mean distance of the
// blockers found, (3) the penumbra width (d_receiver − d_blocker)/d_blocker × light radius,
// (4) rotated Poisson PCF over that width. Every rotation comes from the pixel's counter-based
// random number (core/rng.h), never the thread. README "PCSS" gives the geometry.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "techniques/map_filter.h"
#include "techniques/map_lookup.h"
#include "techniques/poisson_disk.h"

namespace shadowlab {
namespace {

void parse_keys(SpecReader& r, const std::string& name, const char* flag, MapParams& p) {
  PcssKeys& k = p.pcss;
  // "light" (the default) is the scene light's radius, known only at lookup.
  if (!r.is_word("light_size", "light")) k.light_size = r.get_double("light_size", k.light_size, 0.0, 100.0);
  k.search = r.get_int("search", k.search, 1, 256);
  k.taps = r.get_int("taps", k.taps, 1, 256);
  k.search_near = r.get_double("search_near", k.search_near, 0.01, 0.99);
  read_rpdb(r, name, flag, p);
}

std::string keys_text(const MapParams& p) {
  return fmt::format("light_size=light,search={},taps={},search_near={:g},rpdb=1", p.pcss.search,
                     p.pcss.taps, p.pcss.search_near);
}

void filter(const MapParams&, LightMap&) {}  // the stored distances are the map

struct PcssContext {
  const FaceLayout& layout;
  const std::vector<std::vector<float>>& dist;
  PoissonDisk search, taps;
  double radius;       // light radius / far (normalised distance units)
  double search_near;  // nearest blocker searched for, × the receiver's distance
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

// The four stages for one receiver. Angles (radians, seen from the light) become texels by the
// face's texels per plane unit × ρ, ρ = √(1 + u² + v²) the distance from the light to the
// receiver's point on the unit image plane (the isotropic, tangential scale of the gnomonic
// map; radially it stretches by another ρ, ignored).
float pcss_visibility(const PcssContext& c, const Receiver& r) {
  const LightFace& f = c.layout.faces[size_t(r.face)];
  const float per_plane = float(f.width) / (f.right_edge - f.left);  // texels per plane unit
  const float u = f.left + r.st.x / per_plane;
  const float v = f.top - r.st.y * (f.top - f.bottom) / float(f.height);
  // (The paraboloid map is conformal, with 2/(1 + u² + v²) radians per plane unit.)
  const float texels_per_radian = f.paraboloid ? per_plane * 0.5f * (1.0f + u * u + v * v)
                                               : per_plane * std::sqrt(1.0f + u * u + v * v);
  const double t = double(r.depth);
  const float max_radius = 0.5f * float(std::max(f.width, f.height));
  // 1. Blocker search: blockers at s·t or farther can hide part of the light from the receiver
  //    only within the angle R·(t − s·t)/(s·t·t) of its direction.
  const double s = c.search_near;
  const float search_radius = std::clamp(
      float(c.radius * (1.0 - s) / (s * t)) * texels_per_radian, 1.0f, max_radius);
  const vec2 rot_s = poisson_rotation(r.pixel ^ (size_t(1) << 62));
  double blocker_sum = 0.0;
  int blockers = 0;
  for (const vec2& q : c.search.points) {
    const vec2 st(r.st.x + search_radius * (rot_s.x * q.x - rot_s.y * q.y),
                  r.st.y + search_radius * (rot_s.y * q.x + rot_s.x * q.y));
    const float z = depth_at(c, r.face, st);
    if (z < r.depth + glm::dot(r.grad, st - r.st)) {  // grad: rpdb's plane (else 0)
      blocker_sum += double(z);
      ++blockers;
    }
  }
  if (blockers == 0) return 1.0f;
  // 2–3. Mean blocker distance and the penumbra's angular radius R·(t − t_b)/(t_b·t).
  const double tb = blocker_sum / double(blockers);
  const float radius =
      std::clamp(float(c.radius * (t - tb) / (tb * t)) * texels_per_radian, 1.0f, max_radius);
  // 4. Rotated Poisson PCF over that radius.
  const vec2 rot = poisson_rotation(r.pixel);
  float lit = 0.0f;
  for (const vec2& q : c.taps.points) {
    const vec2 st(r.st.x + radius * (rot.x * q.x - rot.y * q.y),
                  r.st.y + radius * (rot.y * q.x + rot.x * q.y));
    lit += compare_at(c, r, st);
  }
  return lit / float(c.taps.points.size());
}

void lookup(const Scene& scene, const GBuffer& g, const MapParams& p, const LightMap& map,
            ImageF& mask, ImageU32* texels) {
  const double light = p.pcss.light_size < 0.0 ? double(scene.light.radius) : p.pcss.light_size;
  const PcssContext c{map.layout,
                      map.dist.distance,
                      poisson_disk(p.pcss.search),
                      poisson_disk(p.pcss.taps),
                      light / double(scene.light.far),
                      p.pcss.search_near};
  lookup_pixels(scene, g, p, map, mask, texels,
                [&](const Receiver& r) { return pcss_visibility(c, r); });
}

// Search taps read 1 texel, PCF taps 2×2.
uint64_t taps_per_lookup(const MapParams& p) {
  return uint64_t(p.pcss.search) + 4 * uint64_t(p.pcss.taps);
}
uint64_t tap_bytes(const MapParams&) { return 4; }
uint64_t stored_planes(const MapParams&) { return 0; }

}  // namespace

const MapFilterOps kPcss = {"pcss",     "percentage-closer soft shadows (blocker search + Poisson PCF)",
                            MapFilter::Pcss, parse_keys, keys_text, filter, lookup,
                            taps_per_lookup, tap_bytes, stored_planes};

}  // namespace shadowlab
