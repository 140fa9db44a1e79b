#include "raster/pipeline.h"

namespace shadowlab {

std::vector<MeshView> scene_mesh_views(const Scene& scene) {
  std::vector<MeshView> views;
  views.reserve(scene.meshes.size());
  for (const Mesh& m : scene.meshes)
    views.push_back({m.positions.data(), m.positions.size(), m.indices.data(), m.triangle_count()});
  return views;
}

std::vector<uint32_t> scene_first_triangles(const Scene& scene) {
  std::vector<uint32_t> first(scene.meshes.size() + 1, 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    first[m + 1] = first[m] + uint32_t(scene.meshes[m].triangle_count());
  return first;
}

}  // namespace shadowlab
