#include "raytrace/face_rays.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace shadowlab {
namespace {

constexpr int kTile = 8;  // 8 × 8 texels per task and per ray stream

using dmat3 = glm::dmat3;
using dmat4 = glm::dmat4;
using dvec4 = glm::dvec4;

// True when the 3×3 part of m is a rotation (orthonormal columns, determinant +1) to within
// float rounding of the matrix entries.
bool is_rigid(const dmat4& m) {
  const dmat3 r(m);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::fabs(glm::dot(r[i], r[j]) - (i == j ? 1.0 : 0.0)) > 1e-4) return false;
  return glm::determinant(r) > 0.0;
}

}  // namespace

PrimaryHits perspective_rays(const EmbreeScene& rt, const mat4& view, const mat4& proj, int width,
                             int height, float max_depth) {
  SL_CHECK(width >= 0 && height >= 0);
  const dmat4 v(view), p(proj);
  SL_CHECK(is_rigid(v));
  // Perspective: the clip w row is (0, 0, −1, 0), i.e. w_clip = −z_view.
  SL_CHECK(p[0][3] == 0.0 && p[1][3] == 0.0 && p[2][3] == -1.0 && p[3][3] == 0.0);
  SL_CHECK(glm::determinant(p) != 0.0);

  PrimaryHits hits;
  hits.width = width;
  hits.height = height;
  const size_t count = size_t(width) * size_t(height);
  hits.mesh_id.assign(count, kNoPrimitive);
  hits.prim_id.assign(count, kNoPrimitive);
  hits.depth.assign(count, std::numeric_limits<float>::infinity());

  // Near plane on the view axis: z_clip + w_clip = p22·z + p32 − z = 0 at z = −near. Texel rays
  // have view z = −t, so the clip test z_clip >= −w_clip is t >= near for every one of them as
  // long as the projection has no oblique near plane (p02 = p12 = 0, checked).
  SL_CHECK(p[0][2] == 0.0 && p[1][2] == 0.0);
  const double near = p[3][2] / (p[2][2] - 1.0);
  SL_CHECK(near > 0.0);

  const dmat4 inv_proj = glm::inverse(p);
  const dmat4 inv_view = glm::inverse(v);
  const dmat3 to_world(inv_view);
  const vec3 eye(dvec3(inv_view * dvec4(0.0, 0.0, 0.0, 1.0)));

  const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  auto* rtc_scene = static_cast<RTCScene>(rt.native_scene());
  parallel_for(0, size_t(tiles_x) * size_t(tiles_y), [&](size_t t) {
    const int x0 = int(t % size_t(tiles_x)) * kTile, y0 = int(t / size_t(tiles_x)) * kTile;
    const int x1 = std::min(x0 + kTile, width), y1 = std::min(y0 + kTile, height);
    RTCRayHit rays[kTile * kTile];
    size_t texel[kTile * kTile];
    unsigned k = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        // NDC of the texel centre (image y down, NDC y up), unprojected to view space and
        // scaled to view z = −1.
        const double ndc_x = 2.0 * (x + 0.5) / width - 1.0;
        const double ndc_y = 1.0 - 2.0 * (y + 0.5) / height;
        const dvec4 q = inv_proj * dvec4(ndc_x, ndc_y, 0.0, 1.0);
        const dvec3 dir_view = dvec3(q) / -q.z;
        const vec3 dir(to_world * dir_view);
        RTCRayHit& r = rays[k];
        r.ray.org_x = eye.x;
        r.ray.org_y = eye.y;
        r.ray.org_z = eye.z;
        r.ray.tnear = float(near);
        r.ray.dir_x = dir.x;
        r.ray.dir_y = dir.y;
        r.ray.dir_z = dir.z;
        r.ray.time = 0.0f;
        r.ray.tfar = max_depth;
        r.ray.mask = 0xFFFFFFFFu;
        r.ray.id = 0;
        r.ray.flags = 0;
        r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        r.hit.primID = RTC_INVALID_GEOMETRY_ID;
        r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        texel[k++] = size_t(y) * size_t(width) + size_t(x);
      }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // the rays of a tile are nearly parallel
    rtcIntersect1M(rtc_scene, &ctx, rays, k, sizeof(RTCRayHit));
    for (unsigned i = 0; i < k; ++i) {
      if (rays[i].hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      hits.mesh_id[texel[i]] = rays[i].hit.geomID;
      hits.prim_id[texel[i]] = rays[i].hit.primID;
      hits.depth[texel[i]] = rays[i].ray.tfar;
    }
  });
  rt.throw_if_error("tracing perspective-view rays");
  return hits;
}

PrimaryHits face_rays(const EmbreeScene& rt, const mat4& view, const mat4& proj, int res,
                      float max_depth) {
  return perspective_rays(rt, view, proj, res, res, max_depth);
}

}  // namespace shadowlab
