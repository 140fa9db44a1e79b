// Rays per second of soft_visibility on a few-thousand-triangle scene (disabled by default; no
// timed assertions). Run with
//   ./build-rt/tests/test_raytrace --gtest_also_run_disabled_tests --gtest_filter='*Throughput*'
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "core/parallel.h"
#include "core/timer.h"
#include "raytrace/embree_scene.h"
#include "raytrace/visibility.h"

namespace shadowlab {
namespace {

// UV sphere of `rings` × `segments` quads (2 triangles each).
Mesh uv_sphere(vec3 centre, float radius, int rings, int segments) {
  Mesh m;
  m.name = "sphere";
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float th = 3.14159265f * float(r) / float(rings);
      const float ph = 6.28318531f * float(s) / float(segments);
      m.positions.push_back(centre + radius * vec3(std::sin(th) * std::cos(ph), std::cos(th),
                                                   -std::sin(th) * std::sin(ph)));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * (segments + 1) + s), b = a + 1;
      const uint32_t c = a + uint32_t(segments + 1), d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
  compute_vertex_normals(m);
  return m;
}

// GBuffer from Embree primary rays (stands in for the camera pass): position on the ray,
// geometric normal of the hit triangle turned toward the eye.
GBuffer gbuffer_from_rays(const EmbreeScene& rt, const Scene& scene) {
  const Camera& c = scene.camera;
  const PrimaryHits hits = primary_visibility(rt, c);
  GBuffer g;
  g.resize(c.width, c.height);
  const vec3 f = glm::normalize(c.target - c.eye);
  const vec3 s = glm::normalize(glm::cross(f, c.up));
  const vec3 u = glm::cross(s, f);
  const float t = std::tan(glm::radians(c.fov_y_deg) * 0.5f);
  const float aspect = float(c.width) / float(c.height);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const size_t i = size_t(y) * size_t(c.width) + size_t(x);
      if (hits.mesh_id[i] == kNoPrimitive) continue;
      const float nx = 2.0f * (x + 0.5f) / c.width - 1.0f, ny = 1.0f - 2.0f * (y + 0.5f) / c.height;
      const vec3 dir = s * (nx * t * aspect) + u * (ny * t) + f;
      const Mesh& m = scene.meshes[hits.mesh_id[i]];
      const uint32_t* tri = &m.indices[size_t(hits.prim_id[i]) * 3];
      vec3 n = glm::normalize(glm::cross(m.positions[tri[1]] - m.positions[tri[0]],
                                         m.positions[tri[2]] - m.positions[tri[0]]));
      if (glm::dot(n, dir) > 0.0f) n = -n;
      g.position[i] = c.eye + hits.depth[i] * dir;
      g.geo_normal[i] = n;
      g.normal[i] = n;
      g.depth[i] = hits.depth[i];
      g.mesh_id[i] = hits.mesh_id[i];
      g.prim_id[i] = hits.prim_id[i];
      g.covered[i] = 1;
    }
  return g;
}

TEST(SoftVisibility, DISABLED_Throughput) {
  Scene s;
  s.name = "throughput";
  s.materials.push_back(Material{});
  Mesh floor;
  floor.positions = {vec3(-8, 0, 8), vec3(8, 0, 8), vec3(8, 0, -8), vec3(-8, 0, -8)};
  floor.indices = {0, 1, 2, 0, 2, 3};
  compute_vertex_normals(floor);
  s.meshes.push_back(floor);
  s.meshes.push_back(uv_sphere(vec3(0.0f, 1.2f, 0.0f), 1.0f, 32, 48));      // 3072 triangles
  s.meshes.push_back(uv_sphere(vec3(-2.0f, 0.6f, 1.0f), 0.5f, 16, 24));     // 768 triangles
  s.meshes.push_back(uv_sphere(vec3(1.8f, 0.5f, -1.2f), 0.4f, 16, 24));     // 768 triangles
  s.light.position = vec3(1.0f, 6.0f, 1.5f);
  s.light.radius = 0.8f;
  s.camera.eye = vec3(0.0f, 5.0f, 7.0f);
  s.camera.target = vec3(0.0f, 0.5f, 0.0f);
  s.camera.width = 256;
  s.camera.height = 256;
  const EmbreeScene rt(s);
  const GBuffer g = gbuffer_from_rays(rt, s);
  const int spp = 64;
  size_t lit_facing = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i)
    lit_facing += g.covered[i] && glm::dot(g.geo_normal[i], s.light.position - g.position[i]) > 0.0f;
  ImageF mask;
  // Wall time (median of 3) and process CPU time per run (robust on a loaded machine).
  const std::clock_t c0 = std::clock();
  const double ms = median_ms(3, [&] { mask = soft_visibility(rt, s, g, spp, 1); });
  const double cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC / 3.0;
  double mean = 0.0;
  for (float v : mask.data) mean += v;
  const double rays = double(lit_facing) * spp;  // upper bound: below-horizon samples skip the ray
  std::printf("triangles %zu, %dx%d, spp %d, threads %d: %.1f ms wall (%.1f ms CPU), %.0f rays "
              "(<=), %.2f Mrays/s wall, %.2f Mrays/s per CPU-second, mean visibility %.4f\n",
              s.triangle_count(), g.width, g.height, spp, thread_count(), ms, cpu_ms, rays,
              rays / ms * 1e-3, rays / cpu_ms * 1e-3, mean / double(mask.data.size()));
  // Same GBuffer against an empty Embree scene: the cost of sampling and bookkeeping alone.
  Scene empty = s;
  empty.meshes.clear();
  const EmbreeScene rt_empty(empty);
  const std::clock_t c1 = std::clock();
  const double ms_empty = median_ms(3, [&] { mask = soft_visibility(rt_empty, empty, g, spp, 1); });
  const double cpu_empty = 1000.0 * double(std::clock() - c1) / CLOCKS_PER_SEC / 3.0;
  std::printf("same GBuffer, empty scene (sampling overhead): %.1f ms wall (%.1f ms CPU)\n",
              ms_empty, cpu_empty);
}

}  // namespace
}  // namespace shadowlab
