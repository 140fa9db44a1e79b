#include "techniques/shading/scene_shading.h"

#include <algorithm>

#include "core/error.h"
#include "core/gbuffer_shading.h"
#include "core/parallel.h"
#include "core/texture.h"
#include "techniques/shading/projector_shading.h"

namespace shadowlab {

ImageF shade_scene(const Scene& scene, const GBuffer& g, const ImageF& visibility, float ambient) {
  SL_CHECK_EQ(visibility.pixel_count(), g.pixel_count());
  if (scene.projector.enabled) {
    ProjectorShading s;
    s.ambient = ambient;
    return shade_projector(scene, g, visibility, s);
  }
  ImageF out(g.width, g.height, 3, 0.0f);
  float* planes[3] = {out.plane(0), out.plane(1), out.plane(2)};
  const vec3 light = scene.light.position;
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (!g.covered[i]) continue;
      const Mesh& mesh = scene.meshes[g.mesh_id[i]];
      const Material& mat = scene.materials[size_t(mesh.material)];
      const ShadingAttributes a = shading_attributes(scene, g, i);
      const vec3 albedo = mat.color_texture >= 0 && !mesh.uvs.empty()
                              ? mat.color_factor * sample_rgb(scene.textures[size_t(mat.color_texture)], a.uv)
                              : mat.albedo;
      const vec3 to_light = light - g.position[i];
      const float len = glm::length(to_light);
      const float ndl = len > 0.0f ? std::max(0.0f, glm::dot(a.normal, to_light / len)) : 0.0f;
      const vec3 c = albedo * (ambient + ndl * visibility.data[i]);
      for (int k = 0; k < 3; ++k) planes[k][i] = c[k];
    }
  });
  return out;
}

}  // namespace shadowlab
