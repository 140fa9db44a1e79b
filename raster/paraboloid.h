#pragma once
// The dual-paraboloid projection (Brabec, Annen & Seidel 2002) as a per-vertex transform for
// the rasterizer: a direction d̂ from the centre, with z = d̂·forward, maps to the image-plane
// point (d̂·right, d̂·up) / (1 + z), the unit disk holding the hemisphere z >= 0. It is not a
// matrix: it is applied to the vertices and the rasterizer interpolates linearly between
// them, so a straight edge stays straight in the image where the true image of the edge is a
// curve (the layout's known error, docs/techniques/layouts.md).
//
// Clip coordinates: w = |p − centre| (so 1/w, which the depth test keeps, is the reciprocal
// radial distance), x, y = the image point mapped to NDC by the face's extent, times w; and
// z/w = 2(z + behind)/(1 + behind) − 1, so the near-plane clip (z >= −w) keeps z >= −behind:
// a margin past the hemisphere's rim for the face's guard band.
#include "core/math.h"

namespace shadowlab {

struct ParaboloidProjection {
  vec3 centre{0.0f}, right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, 1};
  float left = -1.0f, right_edge = 1.0f, bottom = -1.0f, top = 1.0f;  // image-plane extent
  float behind = 0.5f;  // rim margin: z >= -behind is kept
};

// Image-plane point of direction `d` (any length > 0) from the centre. The denominator is kept
// >= 1e-3 so a vertex straight behind (z = −1) stays finite; it lies past the margin and is
// clipped, only its interpolation towards the kept vertices uses the value.
inline vec2 paraboloid_point(const ParaboloidProjection& p, const vec3& d) {
  const float r = glm::length(d);
  const float z = glm::dot(d, p.forward) / r;
  const float den = r * std::max(1.0f + z, 1e-3f);
  return vec2(glm::dot(d, p.right) / den, glm::dot(d, p.up) / den);
}

inline vec4 paraboloid_clip(const ParaboloidProjection& p, const vec3& pos) {
  const vec3 d = pos - p.centre;
  const float r = glm::length(d);
  const vec2 q = paraboloid_point(p, d);
  const float z = glm::dot(d, p.forward) / r;
  const float nx = (2.0f * q.x - (p.left + p.right_edge)) / (p.right_edge - p.left);
  const float ny = (2.0f * q.y - (p.bottom + p.top)) / (p.top - p.bottom);
  const float nz = 2.0f * (z + p.behind) / (1.0f + p.behind) - 1.0f;
  return vec4(nx * r, ny * r, nz * r, r);
}

}  // namespace shadowlab
