#pragma once
// Per-pixel lookup machinery shared by the face-map techniques: the receiver's face, texel
// coordinates, texel index and biased depth; bilinear taps; and the pixel loop that applies
// design.md §4's mask rules (no geometry: 1; facing away from the light: 0).
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/gbuffer.h"
#include "core/image.h"
#include "core/parallel.h"
#include "core/scene.h"
#include "techniques/face_map_params.h"
#include "techniques/light_faces.h"
#include "techniques/normal_offset.h"
#include "techniques/technique.h"

namespace shadowlab {

struct Receiver {
  int face = 0;
  vec2 st{0.0f};       // continuous texel coordinates in the face's image
  float depth = 0.0f;  // biased radial distance / far (what the map's values are compared with)
  uint32_t texel = 0;  // texel index: face × texels per face + y × width + x
};

// Computes the lookup of surface point p with geometric normal n (facing the light, p != L):
// normal offset, face, texel coordinates, constant + slope bias. `reach` is the filter's reach
// in texels (PCF: (pcf + 1)/2; moment maps: 1) that scales the slope term.
inline Receiver make_receiver(const FaceLayout& layout, const PointLight& light,
                              const FaceMapParams& p, float reach, const vec3& pos, const vec3& n) {
  const float plane_texel = face_texel_plane_size(layout.faces[0]);
  const vec3 to_p0 = pos - light.position;
  const float dist0 = glm::length(to_p0);
  const float cos_t = std::clamp(glm::dot(n, -to_p0) / dist0, 1e-4f, 1.0f);
  vec3 to_p = to_p0;
  float dist = dist0;
  if (p.normal > 0.0f) {
    to_p = normal_offset_point(pos, n, light.position, p.normal, plane_texel) - light.position;
    dist = glm::length(to_p);
  }
  Receiver r;
  r.face = face_of(layout, to_p);
  const LightFace& f = layout.faces[size_t(r.face)];
  r.st = face_texel_coords(f, to_p);
  const int tx = std::clamp(int(std::max(r.st.x, -1.0f)), 0, f.width - 1);
  const int ty = std::clamp(int(std::max(r.st.y, -1.0f)), 0, f.height - 1);
  r.texel = uint32_t(size_t(r.face) * f.texel_count() + size_t(ty) * size_t(f.width) + size_t(tx));
  // World size of a texel at the receiver, across the ray: distance × plane size × cos(angle
  // to the face axis) = plane size × (p - L)·forward (plane units shrink by cos towards the
  // face's edge).
  const float texel_world = plane_texel * glm::dot(to_p, f.forward);
  const float tan_t = std::min(std::sqrt(1.0f - cos_t * cos_t) / cos_t, 10.0f);
  const float bias = p.bias + p.slope * reach * texel_world * tan_t;
  r.depth = (dist - bias) / light.far;
  return r;
}

// Bilinear footprint of continuous coordinates st in a w × h image: texels (x0, y0) and
// (x0 + 1, y0 + 1), clamped to the image, with weights fx, fy of the +1 texels.
struct Bilinear {
  int x0, y0, x1, y1;
  float fx, fy;
};
inline Bilinear bilinear_taps(vec2 st, int w, int h) {
  const float gx = st.x - 0.5f, gy = st.y - 0.5f;
  // floor without libm (|g| is far below 2^31 here): truncate, step down for negative
  // non-integers. std::floor is a long sequence on the SSE2 baseline.
  auto floor_f = [](float g) {
    const float t = float(int(g));
    return t > g ? t - 1.0f : t;
  };
  const float flx = floor_f(gx), fly = floor_f(gy);
  Bilinear b;
  b.fx = gx - flx;
  b.fy = gy - fly;
  const int ix = int(flx), iy = int(fly);
  b.x0 = std::clamp(ix, 0, w - 1);
  b.x1 = std::clamp(ix + 1, 0, w - 1);
  b.y0 = std::clamp(iy, 0, h - 1);
  b.y1 = std::clamp(iy + 1, 0, h - 1);
  return b;
}

// Faces the lookups of the covered, light-facing pixels land in (taps stay in the face's guard).
std::vector<bool> faces_needed(const Scene& scene, const GBuffer& g, const FaceLayout& layout,
                               const FaceMapParams& p);

// The pixel loop: visibility(receiver) for every covered, light-facing pixel (on the projector
// layout: inside the projector's frustum, else 0); texel indices
// when `texels` is given. (faces_light() is false for a receiver at the light itself, so every
// receiver reaching make_receiver() has a distance > 0.)
template <class Visibility>
void lookup_faces(const Scene& scene, const GBuffer& g, const FaceLayout& layout,
                  const FaceMapParams& p, float reach, ImageF& mask, ImageU32* texels,
                  const Visibility& visibility) {
  shape_single_channel(mask, g.width, g.height);
  if (texels) shape_single_channel(*texels, g.width, g.height);
  const PointLight& light = scene.light;
  const bool projector = layout.kind == FaceLayoutKind::Projector;
  const ProjectorFrame frame = projector ? projector_frame(scene.projector) : ProjectorFrame{};
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
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
      const Receiver r = make_receiver(layout, light, p, reach, g.position[i], g.geo_normal[i]);
      if (texels) texels->data[i] = r.texel;
      mask.data[i] = std::clamp(visibility(r), 0.0f, 1.0f);
    }
  });
}

}  // namespace shadowlab
