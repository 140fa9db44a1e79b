#pragma once
// Clipping of one clip-space triangle against the near plane (z >= -w) and, only where the
// triangle leaves it, the x/y guard band. Each output vertex carries its barycentric
// coordinates with respect to the original triangle so attributes are interpolated from the
// original vertices (no attribute work at clip time).
#include <cstdint>

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

// Per-vertex outcode: bit p (0..4) set when the vertex lies beyond frustum plane p (near,
// right, left, top, bottom: x, y in [-w, w], z >= -w); bit 5 + p when beyond the same plane
// of the guard band; kOutNonFinite when a coordinate is NaN or infinite.
constexpr uint32_t kOutFrustum = 0x1F, kOutGuard = 0x1F << 5, kOutNonFinite = 1u << 10;
uint32_t vertex_outcode(const vec4& v, float guard_x, float guard_y);

// Classifies a triangle from its vertices' outcodes: Outside if all three lie beyond one
// frustum plane; Inside if none lies beyond the near plane or the guard band.
// guard_x, guard_y: guard-band half extents in NDC units (> 1).
inline ClipClass classify_outcodes(uint32_t a, uint32_t b, uint32_t c) {
  if (a & b & c & kOutFrustum) return ClipClass::Outside;
  if ((a | b | c) & kOutGuard) return ClipClass::NeedsClip;
  return ClipClass::Inside;
}
ClipClass classify_triangle(const vec4& a, const vec4& b, const vec4& c, float guard_x,
                            float guard_y);

// Sutherland–Hodgman clipping of triangle (a, b, c) against the near plane and the guard band.
// Returns the convex polygon (possibly empty).
ClipPolygon clip_triangle(const vec4& a, const vec4& b, const vec4& c, float guard_x,
                          float guard_y);

}  // namespace shadowlab
