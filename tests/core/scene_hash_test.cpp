// The scene content hash of provenance: it changes with anything that renders differently and
// not with names.
#include <gtest/gtest.h>

#include "core/scene_hash.h"

namespace shadowlab {
namespace {

Scene triangle_scene() {
  Scene s;
  s.name = "t";
  Mesh m;
  m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
  m.normals = {vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1)};
  m.indices = {0, 1, 2};
  s.meshes.push_back(m);
  s.materials.push_back(Material{});
  s.light.position = vec3(0, 0, 3);
  return s;
}

TEST(SceneHash, ChangesWithWhatRendersAndNotWithNames) {
  const Scene a = triangle_scene();
  const std::string h = scene_hash(a);
  ASSERT_EQ(h.size(), 16u);
  EXPECT_EQ(h.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_EQ(scene_hash(triangle_scene()), h);  // deterministic
  Scene renamed = a;
  renamed.name = "other";
  renamed.meshes[0].name = "m";
  EXPECT_EQ(scene_hash(renamed), h);
  // Each of these renders differently.
  std::vector<Scene> changed(8, a);
  changed[0].meshes[0].positions[1].x = std::nextafter(1.0f, 2.0f);  // one ulp
  changed[1].meshes[0].indices = {0, 2, 1};
  changed[2].light.position.z = 3.5f;
  changed[3].light.radius = 0.1f;
  changed[4].camera.width = 640;
  changed[5].materials[0].alpha_cutoff = 0.25f;
  changed[6].seed = 2;
  changed[7].textures.push_back(ImageF(1, 1, 4));
  for (size_t i = 0; i < changed.size(); ++i) EXPECT_NE(scene_hash(changed[i]), h) << i;
}

}  // namespace
}  // namespace shadowlab
