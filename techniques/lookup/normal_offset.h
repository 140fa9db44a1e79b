#pragma once
// Normal-offset bias, shared by every map-based technique: the lookup point moves along the
// receiver's geometric normal by scale × (texel size at the receiver) × (1 − N·L), so grazing
// receivers, whose acne is worst, move most and receivers facing the light not at all.
#include <algorithm>

#include "core/math.h"

namespace shadowlab {

// p: receiver (world, m); n: unit geometric normal facing the light; light: light position;
// scale: the spec's `normal`; plane_texel: the map's texel size at unit distance on a face axis
// (an upper bound of the texel's angular size anywhere on the face).
inline vec3 normal_offset_point(const vec3& p, const vec3& n, const vec3& light, float scale,
                                float plane_texel) {
  if (scale <= 0.0f) return p;
  const vec3 to_p = p - light;
  const float dist = glm::length(to_p);
  const float cos_t = std::clamp(glm::dot(n, -to_p) / dist, 0.0f, 1.0f);
  return p + n * (scale * dist * plane_texel * (1.0f - cos_t));
}

}  // namespace shadowlab
