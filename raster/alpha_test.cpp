#include "raster/alpha_test.h"

namespace shadowlab {

AlphaScene scene_alpha(const Scene& scene) {
  AlphaScene a;
  a.first_triangle = scene_first_triangles(scene);
  a.meshes.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const Material& mat = scene.materials[size_t(mesh.material)];
    if (mat.alpha_texture < 0 || mesh.triangle_count() == 0) continue;
    // validate_scene and the OBJ loader guarantee uvs on alpha-textured meshes.
    SL_CHECK_EQ(mesh.uvs.size(), mesh.positions.size());
    AlphaMesh& am = a.meshes[m];
    am.texture = &scene.textures[size_t(mat.alpha_texture)];
    am.uvs = mesh.uvs.data();
    am.indices = mesh.indices.data();
    am.cutoff = mat.alpha_cutoff;
    a.any = true;
  }
  return a;
}

}  // namespace shadowlab
