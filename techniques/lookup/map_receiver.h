#pragma once
// Per-pixel lookup machinery of the light-map pipeline (techniques/pipeline/light_map.h), shared by every
// layout and filter: the receiver's face, texel coordinates, texel index and biased depth; the
// bilinear and PCF taps (with cross-face taps for SeamMode::Cross); and the pixel loop that
// applies docs/design.md §4's mask rules (no geometry: 1; facing away from the light: 0).
#include <algorithm>
#include <cstddef>
#include <cmath>
#include <vector>

#include "core/gbuffer.h"
#include "core/image.h"
#include "core/parallel.h"
#include "core/scene.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/pipeline/map_params.h"
#include "techniques/lookup/normal_offset.h"
#include "techniques/registry/technique.h"

namespace shadowlab {

struct Receiver {
  int face = 0;
  vec2 st{0.0f};       // continuous texel coordinates in the face's image
  float depth = 0.0f;  // biased radial distance / far (what the map's values are compared with)
  uint32_t texel = 0;  // texel index: face × texels per face + y × width + x
  size_t pixel = 0;    // the GBuffer pixel (seeds per-pixel random numbers: Poisson PCF)
  vec2 grad{0.0f};     // rpdb: d(depth)/d(st) of the receiver's plane, per texel (else 0)
};

// Receiver-plane depth gradient (rpdb): the normalised radial distance, along the direction
// through texel coordinates st of `f`, to the plane through the lookup point q with geometric
// normal n, differentiated by st at the receiver. With D = forward + u·right + v·up (u, v the
// plane coordinates of st), that distance is ρ = k·|D| / (n·D), k = n·(q − L); so
// ∂ρ/∂u = k·((D·right)/|D| / (n·D) − |D|·(n·right)/(n·D)²), likewise v with up, times
// du/dsx = (right_edge − left)/width and dv/dsy = −(top − bottom)/height. The cosine |n·D|/|D|
// is clamped to >= 0.1 (as the slope term caps tan θ at 10), bounding the gradient at grazing
// angles.
inline vec2 receiver_plane_gradient(const LightFace& f, const vec3& to_q, const vec3& n,
                                    float inv_far);
// The same gradient for any face map (the paraboloid's), by central differences of the exact
// plane distance along the directions through st ± ½ texel (cosine clamped likewise).
inline vec2 receiver_plane_gradient_numeric(const LightFace& f, vec2 st, const vec3& to_q,
                                            const vec3& n, float inv_far) {
  const float k = glm::dot(n, to_q);
  auto dist = [&](float sx, float sy) {
    const vec3 d = face_texel_direction(f, sx, sy);
    float nd = glm::dot(n, d);
    if (std::fabs(nd) < 0.001f) nd = nd < 0.0f ? -0.001f : 0.001f;
    return k / nd;
  };
  return vec2(dist(st.x + 0.5f, st.y) - dist(st.x - 0.5f, st.y),
              dist(st.x, st.y + 0.5f) - dist(st.x, st.y - 0.5f)) *
         inv_far;
}

inline vec2 receiver_plane_gradient(const LightFace& f, const vec3& to_q, const vec3& n,
                                    float inv_far) {
  const float inv_fwd = 1.0f / glm::dot(to_q, f.forward);
  const vec3 D = f.forward + glm::dot(to_q, f.right) * inv_fwd * f.right +
                 glm::dot(to_q, f.up) * inv_fwd * f.up;
  const float len = glm::length(D);
  float nd = glm::dot(n, D);
  if (std::fabs(nd) < 0.001f * len) nd = nd < 0.0f ? -0.001f * len : 0.001f * len;
  const float k = glm::dot(n, to_q);
  auto partial = [&](const vec3& axis) {
    return k * (glm::dot(D, axis) / len / nd - len * glm::dot(n, axis) / (nd * nd));
  };
  return vec2(partial(f.right) * (f.right_edge - f.left) / float(f.width),
              -partial(f.up) * (f.top - f.bottom) / float(f.height)) *
         inv_far;
}

// Texel of a continuous coordinate, clamped to [0, n). Truncation equals floor here: they
// differ only for negative non-integers, which the clamp maps to texel 0 either way (and floorf
// is a long libm-style sequence on the SSE2 baseline).
inline int clamp_texel(float c, int n) { return std::clamp(int(std::max(c, -1.0f)), 0, n - 1); }

// The lookup point of surface point p with geometric normal n: p itself, or its normal-offset
// point (techniques/lookup/normal_offset.h) with the layout's plane texel size.
inline vec3 lookup_point(const FaceLayout& layout, const PointLight& light, const MapParams& p,
                         const vec3& pos, const vec3& n) {
  return p.normal > 0.0f ? normal_offset_point(pos, n, light.position, p.normal,
                                               face_texel_plane_size(layout.faces[0]))
                         : pos;
}

// Computes the lookup of surface point p with geometric normal n (facing the light, p != L):
// normal offset, face, texel coordinates, constant + slope bias. `reach` is the filter's reach
// in texels (map_reach) that scales the slope term.
//
// Texel size at the receiver for the slope term: on the cube layout, plane texel × radial
// distance, csm's rule since its first version (a face's plane texel bounds the texel's angular
// size anywhere on a 90° face); on the wider tetrahedral and projector faces, plane texel ×
// (p − L)·forward, the texel's world size across the ray (the angular size falls by cos² off
// axis, so the radial rule would over-bias a tetrahedral face's corners ~3×). With the default
// slope of 0 on the filtering techniques the rule does not matter there.
inline Receiver make_receiver(const FaceLayout& layout, const PointLight& light,
                              const MapParams& p, float reach, float inv_far, const vec3& pos,
                              const vec3& n) {
  const float plane_texel = face_texel_plane_size(layout.faces[0]);
  const vec3 to_p0 = pos - light.position;
  const float dist0 = glm::length(to_p0);
  // The slope term keeps the receiver's own angle; the lookup uses the offset point.
  const float cos_t = std::clamp(glm::dot(n, -to_p0) / dist0, 1e-4f, 1.0f);
  vec3 to_p = to_p0;
  float dist = dist0;
  if (p.normal > 0.0f) {
    to_p = lookup_point(layout, light, p, pos, n) - light.position;
    dist = glm::length(to_p);
  }
  Receiver r;
  r.face = face_of(layout, to_p);
  const LightFace& f = layout.faces[size_t(r.face)];
  r.st = face_texel_coords(f, to_p);
  const int tx = clamp_texel(r.st.x, f.width), ty = clamp_texel(r.st.y, f.height);
  r.texel = uint32_t(size_t(r.face) * f.texel_count() + size_t(ty) * size_t(f.width) + size_t(tx));
  const float tan_t = std::min(std::sqrt(1.0f - cos_t * cos_t) / cos_t, 10.0f);
  const float k = p.slope * reach;
  float slope_bias;
  if (layout.kind == FaceLayoutKind::Cube) {
    slope_bias = k * plane_texel * dist * tan_t;
  } else if (f.paraboloid) {
    // The paraboloid map is conformal: a texel spans plane texel × 2/(1 + u² + v²) radians.
    const vec2 uv = face_plane_coords(f, r.st);
    slope_bias = k * (plane_texel * dist * 2.0f / (1.0f + glm::dot(uv, uv))) * tan_t;
  } else {
    slope_bias = k * (plane_texel * glm::dot(to_p, f.forward)) * tan_t;
  }
  r.depth = (dist - (p.bias + slope_bias)) * inv_far;
  if (p.rpdb)
    r.grad = f.paraboloid ? receiver_plane_gradient_numeric(f, r.st, to_p, n, inv_far)
                          : receiver_plane_gradient(f, to_p, n, inv_far);
  return r;
}

// Bilinear footprint of continuous coordinates st in a w × h image: texels (x0, y0) and
// (x0 + 1, y0 + 1), clamped to the image, with weights fx, fy of the +1 texels.
struct Bilinear {
  int x0, y0, x1, y1;
  float fx, fy;
};
// floor for |g| < 2^31 without libm: truncate, then step down for negative non-integers.
inline int floor_int(float g) {
  const int i = int(g);
  return float(i) > g ? i - 1 : i;
}
inline Bilinear bilinear_taps(vec2 st, int w, int h) {
  const float gx = st.x - 0.5f, gy = st.y - 0.5f;
  const int ix = floor_int(gx), iy = floor_int(gy);
  Bilinear b;
  b.fx = gx - float(ix);
  b.fy = gy - float(iy);
  b.x0 = std::clamp(ix, 0, w - 1);
  b.x1 = std::clamp(ix + 1, 0, w - 1);
  b.y0 = std::clamp(iy, 0, h - 1);
  b.y1 = std::clamp(iy + 1, 0, h - 1);
  return b;
}

// Texel indices of a bilinear footprint in a w-wide image, in the order (x0,y0), (x1,y0),
// (x0,y1), (x1,y1).
inline void bilinear_indices(const Bilinear& b, int w, size_t idx[4]) {
  idx[0] = size_t(b.y0) * size_t(w) + size_t(b.x0);
  idx[1] = size_t(b.y0) * size_t(w) + size_t(b.x1);
  idx[2] = size_t(b.y1) * size_t(w) + size_t(b.x0);
  idx[3] = size_t(b.y1) * size_t(w) + size_t(b.x1);
}

// True when every tap of an N×N PCF at st lies inside the face's w × h image.
inline bool pcf_taps_inside(vec2 st, int pcf, int w, int h) {
  if (pcf <= 1) return true;
  const int half = (pcf - 1) / 2;
  const int bx = floor_int(st.x - 0.5f) - half, by = floor_int(st.y - 0.5f) - half;
  return bx >= 0 && by >= 0 && bx + pcf < w && by + pcf < h;
}

// Visits the texels of an N×N bilinear-weighted PCF lookup (pcf = 1: the nearest texel) at
// continuous coordinates st of `face`: fn(face, x, y, weight), weights summing to 1, rows then
// columns. Zero weights are skipped (so is their face). A tap beyond the face's image is looked
// up through its texel centre's direction in the face that owns it (SeamMode::Cross; with a
// guard band no tap gets there).
template <class Fn>
void for_each_pcf_tap(const FaceLayout& layout, int face, vec2 st, int pcf, Fn&& fn) {
  const LightFace& f = layout.faces[size_t(face)];
  if (pcf <= 1) {
    fn(face, clamp_texel(st.x, f.width), clamp_texel(st.y, f.height), 1.0f);
    return;
  }
  const float gx = st.x - 0.5f, gy = st.y - 0.5f;
  const int bx = floor_int(gx), by = floor_int(gy);
  const float fx = gx - float(bx), fy = gy - float(by);
  const int half = (pcf - 1) / 2;
  const float norm = 1.0f / float(pcf * pcf);
  for (int j = 0; j <= pcf; ++j) {
    const float wy = j == 0 ? 1.0f - fy : (j == pcf ? fy : 1.0f);
    for (int i = 0; i <= pcf; ++i) {
      const float wx = i == 0 ? 1.0f - fx : (i == pcf ? fx : 1.0f);
      const float w = wx * wy * norm;
      if (w == 0.0f) continue;
      const int tx = bx - half + i, ty = by - half + j;
      if (tx >= 0 && ty >= 0 && tx < f.width && ty < f.height) {
        fn(face, tx, ty, w);
        continue;
      }
      const vec3 dir = face_texel_direction(f, float(tx) + 0.5f, float(ty) + 0.5f);
      const int f2 = face_of(layout, dir);
      const LightFace& g2 = layout.faces[size_t(f2)];
      const vec2 st2 = face_texel_coords(g2, dir);
      fn(f2, clamp_texel(st2.x, g2.width), clamp_texel(st2.y, g2.height), w);
    }
  }
}

// The pixel loop: visibility(receiver) for every covered, light-facing pixel (on the projector
// layout: inside the projector's frustum, else 0); texel indices when `texels` is given.
// Pixels [b, e) of each chunk go to `block(b, e)` first, which returns how many leading pixels
// it handled (a SIMD kernel; 0 = none); the rest run here. (faces_light() is false for a
// receiver at the light itself, so every receiver reaching make_receiver() has a distance > 0.)
template <class Visibility, class Block>
void lookup_faces(const Scene& scene, const GBuffer& g, const FaceLayout& layout,
                  const MapParams& p, ImageF& mask, ImageU32* texels, const Visibility& visibility,
                  const Block& block) {
  shape_single_channel(mask, g.width, g.height);
  if (texels) shape_single_channel(*texels, g.width, g.height);
  const PointLight& light = scene.light;
  const float inv_far = 1.0f / light.far;
  const float reach = map_reach(p);
  const bool projector = layout.kind == FaceLayoutKind::Projector;
  const ProjectorFrame frame = projector ? projector_frame(scene.projector) : ProjectorFrame{};
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    b += block(b, e);
    for (size_t i = b; i < e; ++i) {
      if (texels) texels->data[i] = kNoTexel;
      if (!g.covered[i]) {
        mask.data[i] = 1.0f;
        continue;
      }
      vec2 slide_st;
      if (!faces_light(g, i, light.position) ||
          (projector && !projector_slide_coords(frame, light.position, g.position[i], slide_st))) {
        mask.data[i] = 0.0f;
        continue;
      }
      Receiver r =
          make_receiver(layout, light, p, reach, inv_far, g.position[i], g.geo_normal[i]);
      r.pixel = i;
      if (texels) texels->data[i] = r.texel;
      mask.data[i] = std::clamp(visibility(r), 0.0f, 1.0f);
    }
  });
}

}  // namespace shadowlab
