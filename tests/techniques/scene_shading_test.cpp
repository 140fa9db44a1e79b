// The shaded image (techniques/shading/scene_shading.h) on the plane scene, where N·L is known in closed
// form: the floor's normal is +y and the light 2 m above the origin, so a floor point (x, 0, z)
// has N·L = 2 / √(x² + 4 + z²).
#include <gtest/gtest.h>

#include <cmath>

#include "techniques/shading/scene_shading.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

TEST(SceneShading, PlaneSceneMatchesTheClosedForm) {
  const Scene scene = test::small_scene("plane", 64, 48);
  const GBuffer g = render_gbuffer(scene);
  ImageF vis(g.width, g.height, 1, 0.0f);
  for (size_t i = 0; i < vis.data.size(); ++i) vis.data[i] = float(i % 3) * 0.5f;  // 0, 0.5, 1
  const float ambient = 0.2f;
  const ImageF out = shade_scene(scene, g, vis, ambient);
  ASSERT_EQ(out.channels, 3);
  const float albedo = scene.materials[size_t(scene.meshes[0].material)].albedo.x;
  size_t covered = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i]) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(out.data[size_t(c) * g.pixel_count() + i], 0.0f);
      continue;
    }
    ++covered;
    const vec3 p = g.position[i];
    const double ndl = 2.0 / std::sqrt(double(p.x) * p.x + 4.0 + double(p.z) * p.z);
    const double expected = double(albedo) * (ambient + ndl * vis.data[i]);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(out.data[size_t(c) * g.pixel_count() + i], expected, 2e-6) << i;
  }
  EXPECT_GT(covered, g.pixel_count() / 2);
}

}  // namespace
}  // namespace shadowlab
