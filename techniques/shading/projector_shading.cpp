#include "techniques/shading/projector_shading.h"

#include <algorithm>

#include "core/error.h"
#include "core/gbuffer_shading.h"
#include "core/parallel.h"

namespace shadowlab {

ImageF shade_projector(const Scene& scene, const GBuffer& g, const ImageF& visibility,
                       const ProjectorShading& shading) {
  SL_CHECK(scene.projector.enabled);
  SL_CHECK_EQ(visibility.pixel_count(), g.pixel_count());
  const Projector& proj = scene.projector;
  const ProjectorFrame frame = projector_frame(proj);
  ImageF out(g.width, g.height, 3, 0.0f);
  float* planes[3] = {out.plane(0), out.plane(1), out.plane(2)};
  parallel_for_chunks(g.pixel_count(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (!g.covered[i]) continue;
      const Mesh& mesh = scene.meshes[g.mesh_id[i]];
      const vec3 albedo = scene.materials[size_t(mesh.material)].albedo;
      vec3 c = shading.ambient * albedo;
      const float vis = visibility.data[i];
      if (vis > 0.0f) {
        const vec3 to_light = proj.position - g.position[i];
        const float ndl = std::max(0.0f, glm::dot(shading_attributes(scene, g, i).normal, glm::normalize(to_light)));
        c += projector_light(proj, frame, g.position[i]) * albedo * (ndl * vis);
      }
      for (int k = 0; k < 3; ++k) planes[k][i] = c[k];
    }
  });
  return out;
}

ImageF luminance(const ImageF& rgb) {
  SL_CHECK_EQ(rgb.channels, 3);
  ImageF y(rgb.width, rgb.height, 1);
  const float* r = rgb.plane(0);
  const float* g = rgb.plane(1);
  const float* b = rgb.plane(2);
  for (size_t i = 0; i < y.pixel_count(); ++i) y.data[i] = 0.2126f * r[i] + 0.7152f * g[i] + 0.0722f * b[i];
  return y;
}

}  // namespace shadowlab
