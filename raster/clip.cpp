#include "raster/clip.h"

#include <cmath>

namespace shadowlab {
namespace {

// Signed distances to the planes, positive inside: near (z + w), then the guard band
// (gx*w - x, gx*w + x, gy*w - y, gy*w + y).
constexpr int kPlanes = 5;

float plane_distance(int plane, const vec4& p, float gx, float gy) {
  switch (plane) {
    case 0: return p.z + p.w;
    case 1: return gx * p.w - p.x;
    case 2: return gx * p.w + p.x;
    case 3: return gy * p.w - p.y;
    default: return gy * p.w + p.y;
  }
}

// Frustum planes for the trivial reject: the real viewport (x, y in [-w, w]) and near.
float frustum_distance(int plane, const vec4& p) { return plane_distance(plane, p, 1.0f, 1.0f); }

}  // namespace

uint32_t vertex_outcode(const vec4& v, float guard_x, float guard_y) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w))
    return kOutNonFinite;
  uint32_t code = 0;
  for (int p = 0; p < kPlanes; ++p) {
    if (frustum_distance(p, v) < 0.0f) code |= 1u << p;
    if (plane_distance(p, v, guard_x, guard_y) < 0.0f) code |= 1u << (5 + p);
  }
  return code;
}

ClipClass classify_triangle(const vec4& a, const vec4& b, const vec4& c, float guard_x,
                            float guard_y) {
  return classify_outcodes(vertex_outcode(a, guard_x, guard_y), vertex_outcode(b, guard_x, guard_y),
                           vertex_outcode(c, guard_x, guard_y));
}

ClipPolygon clip_triangle(const vec4& a, const vec4& b, const vec4& c, float guard_x,
                          float guard_y) {
  ClipPolygon poly;
  poly.v[0] = {a, vec3(1, 0, 0)};
  poly.v[1] = {b, vec3(0, 1, 0)};
  poly.v[2] = {c, vec3(0, 0, 1)};
  poly.count = 3;
  for (int p = 0; p < kPlanes && poly.count > 0; ++p) {
    ClipPolygon out;
    for (int i = 0; i < poly.count; ++i) {
      const ClipVertex& s = poly.v[i];
      const ClipVertex& e = poly.v[(i + 1) % poly.count];
      const float ds = plane_distance(p, s.clip, guard_x, guard_y);
      const float de = plane_distance(p, e.clip, guard_x, guard_y);
      if (ds >= 0.0f) out.v[out.count++] = s;
      if ((ds >= 0.0f) != (de >= 0.0f)) {
        // Intersection, always computed from the inside vertex towards the outside one so an
        // edge shared by two triangles is cut at exactly the same point in both.
        const bool s_in = ds >= 0.0f;
        const ClipVertex& in = s_in ? s : e;
        const ClipVertex& outv = s_in ? e : s;
        const float din = s_in ? ds : de;
        const float dout = s_in ? de : ds;
        // In double: a vertex cut at the near plane has a small w that float interpolation
        // between far-apart endpoints would get wrong by ~1e-5 relative, moving it on screen.
        const double t = double(din) / (double(din) - double(dout));
        const glm::dvec4 ci(in.clip), co(outv.clip);
        const glm::dvec3 bi(in.bary), bo(outv.bary);
        out.v[out.count++] = {vec4(ci + t * (co - ci)), vec3(bi + t * (bo - bi))};
      }
    }
    poly = out;
  }
  if (poly.count < 3) poly.count = 0;
  return poly;
}

}  // namespace shadowlab
