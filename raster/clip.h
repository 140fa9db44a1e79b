#pragma once
// Clipping of one clip-space triangle against the near plane (z >= -w) and, only where the
// triangle leaves it, the x/y guard band. Each output vertex carries its barycentric
// coordinates with respect to the original triangle so attributes are interpolated from the
// original vertices (no attribute work at clip time).
#include "core/math.h"

namespace shadowlab {

struct ClipVertex {
  vec4 clip;  // clip-space position
  vec3 bary;  // barycentrics w.r.t. the original triangle
};

// At most 3 + number of planes (5) vertices.
struct ClipPolygon {
  ClipVertex v[9];
  int count = 0;
};

// Outcome of the trivial tests done before any clipping.
enum class ClipClass { Inside, Outside, NeedsClip };

// Classifies a triangle: Outside if all three vertices lie beyond one frustum plane (left,
// right, bottom, top, near); Inside if all lie inside the near plane and the guard band.
// guard_x, guard_y: guard-band half extents in NDC units (> 1).
ClipClass classify_triangle(const vec4& a, const vec4& b, const vec4& c, float guard_x,
                            float guard_y);

// Sutherland–Hodgman clipping of triangle (a, b, c) against the near plane and the guard band.
// Returns the convex polygon (possibly empty).
ClipPolygon clip_triangle(const vec4& a, const vec4& b, const vec4& c, float guard_x,
                          float guard_y);

}  // namespace shadowlab
