#include "core/gbuffer_shading.h"

#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace shadowlab {

dvec3 barycentric_of_point(const vec3& p, const vec3& a, const vec3& b, const vec3& c) {
  // The normal equations of p − a ≈ l1·(b − a) + l2·(c − a) (Ericson, "Real-Time Collision
  // Detection", 3.4): exact for p in the plane, the orthogonal projection otherwise.
  const dvec3 e1 = dvec3(b) - dvec3(a), e2 = dvec3(c) - dvec3(a), r = dvec3(p) - dvec3(a);
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double r1 = glm::dot(r, e1), r2 = glm::dot(r, e2);
  const double den = d11 * d22 - d12 * d12;
  if (!(den > 0.0) || !std::isfinite(den)) return dvec3(1.0 / 3.0);
  const double l1 = (d22 * r1 - d12 * r2) / den, l2 = (d11 * r2 - d12 * r1) / den;
  return dvec3(1.0 - l1 - l2, l1, l2);
}

ShadingAttributes shading_attributes(const Scene& scene, const GBuffer& g, size_t i) {
  SL_CHECK(i < g.pixel_count());
  ShadingAttributes out;
  if (g.has_shading_attributes()) {
    out.normal = g.normal[i];
    out.uv = g.uv[i];
    return out;
  }
  if (!g.covered[i]) return out;
  const Mesh& mesh = scene.meshes[g.mesh_id[i]];
  const uint32_t* idx = &mesh.indices[3 * size_t(g.prim_id[i])];
  const dvec3 l = barycentric_of_point(g.position[i], mesh.positions[idx[0]],
                                       mesh.positions[idx[1]], mesh.positions[idx[2]]);
  const vec3 gn = g.geo_normal[i];
  out.normal = gn;
  if (!mesh.normals.empty()) {
    const dvec3 n = l.x * dvec3(mesh.normals[idx[0]]) + l.y * dvec3(mesh.normals[idx[1]]) +
                    l.z * dvec3(mesh.normals[idx[2]]);
    const double len = glm::length(n);
    if (len > 0.0) out.normal = vec3(n / len);
  }
  if (glm::dot(out.normal, gn) < 0.0f) out.normal = -out.normal;
  if (!mesh.uvs.empty())
    out.uv = vec2(l.x * dvec2(mesh.uvs[idx[0]]) + l.y * dvec2(mesh.uvs[idx[1]]) +
                  l.z * dvec2(mesh.uvs[idx[2]]));
  return out;
}

void fill_shading_attributes(const Scene& scene, GBuffer& g) {
  if (g.has_shading_attributes()) return;
  std::vector<vec3> normal(g.pixel_count());
  std::vector<vec2> uv(g.pixel_count());
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const ShadingAttributes a = shading_attributes(scene, g, i);
      normal[i] = a.normal;
      uv[i] = a.uv;
    }
  });
  g.normal = std::move(normal);
  g.uv = std::move(uv);
}

}  // namespace shadowlab
