#include "raster/gbuffer_pass.h"

#include <algorithm>

#include "core/parallel.h"
#include "raster/pipeline.h"

namespace shadowlab {
namespace {

// Records the winning triangle and its barycentrics per pixel.
struct VisibilityShader {
  static constexpr bool kNeedsAttributes = true;
  int width;
  uint32_t* triangle;
  vec3* bary;
  bool operator()(const Fragment& f) {
    const size_t i = size_t(f.y) * size_t(width) + size_t(f.x);
    triangle[i] = f.triangle;
    bary[i] = vec3(f.bary[0], f.bary[1], f.bary[2]);
    return true;
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
  g.resize(w, h);
  std::vector<uint32_t> triangle(g.pixel_count(), kNoPrimitive);
  std::vector<vec3> bary(g.pixel_count(), vec3(0.0f));
  VisibilityShader shader{w, triangle.data(), bary.data()};
  DepthTarget depth;
  const mat4 view_proj = camera_projection(cam) * camera_view(cam);
  const RasterStats st =
      rasterize(scene_mesh_views(scene), view_proj, CullMode::None, w, h, depth, shader);
  if (stats) *stats = st;

  // Resolve: one attribute evaluation per covered pixel.
  const std::vector<uint32_t> first = scene_first_triangles(scene);
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const uint32_t t = triangle[i];
      if (t == kNoPrimitive) continue;
      const uint32_t m = uint32_t(std::upper_bound(first.begin(), first.end(), t) - first.begin()) - 1;
      const Mesh& mesh = scene.meshes[m];
      const uint32_t p = t - first[m];
      const uint32_t* idx = &mesh.indices[3 * size_t(p)];
      const vec3 l = bary[i];
      const vec3& p0 = mesh.positions[idx[0]];
      const vec3& p1 = mesh.positions[idx[1]];
      const vec3& p2 = mesh.positions[idx[2]];
      const vec3 pos = l.x * p0 + l.y * p1 + l.z * p2;
      vec3 gn = glm::cross(p1 - p0, p2 - p0);
      const float gl = glm::length(gn);
      gn = gl > 0.0f ? gn / gl : vec3(0.0f, 1.0f, 0.0f);
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
      g.depth[i] = 1.0f / depth.inv_w[i];
      g.mesh_id[i] = m;
      g.prim_id[i] = p;
      g.covered[i] = 1;
    }
  });
}

}  // namespace shadowlab
