#include "raster/pipeline.h"

namespace shadowlab {

std::vector<MeshView> scene_mesh_views(const Scene& scene) {
  // Bounds are computed here, once per call: callers rendering several views (cube faces)
  // build the views once and pass them to every rasterize().
  std::vector<MeshView> views;
  views.reserve(scene.meshes.size());
  for (const Mesh& m : scene.meshes) {
    MeshView v{m.positions.data(), m.positions.size(), m.indices.data(), m.triangle_count()};
    if (!m.positions.empty()) {
      v.has_bounds = true;
      v.lo = v.hi = m.positions[0];
      for (const vec3& p : m.positions) {
        v.lo = glm::min(v.lo, p);
        v.hi = glm::max(v.hi, p);
      }
      // A NaN/Inf vertex must only drop its own triangles (counted in the binner), never
      // cull the whole mesh through a NaN bound.
      v.has_bounds = is_finite(v.lo) && is_finite(v.hi);
    }
    views.push_back(v);
  }
  return views;
}

std::vector<uint32_t> scene_first_triangles(const Scene& scene) {
  std::vector<uint32_t> first(scene.meshes.size() + 1, 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    first[m + 1] = first[m] + uint32_t(scene.meshes[m].triangle_count());
  return first;
}

}  // namespace shadowlab
