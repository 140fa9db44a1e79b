#include "raster/gbuffer_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "raster/pipeline.h"

namespace shadowlab {
namespace {

// Camera rays through pixel centres: dir has a unit forward component, so the ray parameter of
// a hit is its view depth (distance along -z in view space).
struct PixelRays {
  vec3 eye, forward, right, up;
  float sx, sy;  // tan(fov/2)·aspect and tan(fov/2)
  int width, height;
  explicit PixelRays(const Camera& c) : eye(c.eye), width(c.width), height(c.height) {
    forward = glm::normalize(c.target - c.eye);
    right = glm::normalize(glm::cross(forward, c.up));
    up = glm::cross(right, forward);
    sy = std::tan(glm::radians(c.fov_y_deg) * 0.5f);
    sx = sy * float(c.width) / float(c.height);
  }
  vec3 dir(int x, int y) const {
    const float nx = (float(x) + 0.5f) / float(width) * 2.0f - 1.0f;
    const float ny = 1.0f - (float(y) + 0.5f) / float(height) * 2.0f;
    return forward + (nx * sx) * right + (ny * sy) * up;
  }
};

}  // namespace

GBuffer render_gbuffer(const Scene& scene, RasterStats* stats) {
  GBuffer g;
  render_gbuffer(scene, g, stats);
  return g;
}

void render_gbuffer(const Scene& scene, GBuffer& g, RasterStats* stats) {
  const Camera& cam = scene.camera;
  const int w = cam.width, h = cam.height;
  g.reshape(w, h);
  // Visibility pass: depth and triangle id only (the depth-only fast path). The target is
  // per calling thread and kept between calls: no page faults in timing loops.
  // (Bound to a plain reference: the worker threads below must see THIS thread's target, not
  // their own thread_local instance.)
  thread_local DepthTarget vis_storage;
  DepthTarget& vis = vis_storage;
  vis.with_ids = true;
  DepthOnlyShader shader;
  const mat4 view_proj = camera_projection(cam) * camera_view(cam);
  const RasterStats st =
      rasterize(scene_mesh_views(scene), view_proj, CullMode::None, w, h, vis, shader);
  if (stats) *stats = st;

  // Resolve, once per pixel: intersect the pixel's camera ray with the visible triangle's
  // plane (barycentrics and view depth), then interpolate the attributes. Every pixel is
  // written, covered or not.
  const std::vector<uint32_t> first = scene_first_triangles(scene);
  const PixelRays rays(cam);
  parallel_for_chunks(size_t(h), 8, [&](size_t y0, size_t y1) {
    uint32_t m = 0;
    for (size_t y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = y * size_t(w) + size_t(x);
        const uint32_t t = vis.ids[i];
        if (t == kNoPrimitive) {
          g.position[i] = vec3(0.0f);
          g.normal[i] = g.geo_normal[i] = vec3(0.0f);
          g.uv[i] = vec2(0.0f);
          g.depth[i] = std::numeric_limits<float>::infinity();
          g.mesh_id[i] = g.prim_id[i] = kNoPrimitive;
          g.covered[i] = 0;
          continue;
        }
        // Neighbouring pixels mostly see the same mesh: try the previous one first.
        if (t < first[m] || t >= first[m + 1])
          m = uint32_t(std::upper_bound(first.begin(), first.end(), t) - first.begin()) - 1;
        const Mesh& mesh = scene.meshes[m];
        const uint32_t p = t - first[m];
        const uint32_t* idx = &mesh.indices[3 * size_t(p)];
        const vec3& p0 = mesh.positions[idx[0]];
        const vec3& p1 = mesh.positions[idx[1]];
        const vec3& p2 = mesh.positions[idx[2]];
        const vec3 e1 = p1 - p0, e2 = p2 - p0;
        const vec3 d = rays.dir(x, int(y));
        // Möller–Trumbore without the inside test (the rasterizer decided coverage).
        const vec3 pv = glm::cross(d, e2);
        const float det = glm::dot(e1, pv);
        vec3 l(1.0f / 3.0f);
        float depth = 1.0f / vis.inv_w[i];
        if (std::fabs(det) > 1e-30f) {
          const float inv_det = 1.0f / det;
          const vec3 s = rays.eye - p0;
          const float u = glm::dot(s, pv) * inv_det;
          const vec3 q = glm::cross(s, e1);
          const float v = glm::dot(d, q) * inv_det;
          const float tt = glm::dot(e2, q) * inv_det;
          // Only trust a hit in front of the eye; edge-on triangles keep the raster depth.
          if (std::isfinite(tt) && tt > 0.0f) {
            l = vec3(1.0f - u - v, u, v);
            depth = tt;
          }
        }
        vec3 gn = glm::cross(e1, e2);
        const float gl = glm::length(gn);
        gn = gl > 0.0f ? gn / gl : vec3(0.0f, 1.0f, 0.0f);
        const vec3 pos = rays.eye + depth * d;
        vec3 sn = gn;
        if (!mesh.normals.empty()) {
          const vec3 n = l.x * mesh.normals[idx[0]] + l.y * mesh.normals[idx[1]] +
                         l.z * mesh.normals[idx[2]];
          const float nl = glm::length(n);
          if (nl > 0.0f) sn = n / nl;
        }
        // Two-sided: make both normals face the eye.
        if (glm::dot(gn, cam.eye - pos) < 0.0f) gn = -gn;
        if (glm::dot(sn, gn) < 0.0f) sn = -sn;
        vec2 uv(0.0f);
        if (!mesh.uvs.empty())
          uv = l.x * mesh.uvs[idx[0]] + l.y * mesh.uvs[idx[1]] + l.z * mesh.uvs[idx[2]];
        g.position[i] = pos;
        g.normal[i] = sn;
        g.geo_normal[i] = gn;
        g.uv[i] = uv;
        g.depth[i] = depth;
        g.mesh_id[i] = m;
        g.prim_id[i] = p;
        g.covered[i] = 1;
      }
  });
}

}  // namespace shadowlab
