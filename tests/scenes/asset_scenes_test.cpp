// The scenes made of the repository's own assets (assets/): the example JSON scene file.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scenes/scene_file.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

TEST(AssetScenes, TwoBunniesExampleLoadsFromTheRepository) {
  std::vector<std::string> notes;
  const Scene s = load_scene_file(test::source_path("assets/scenes/two_bunnies.json"), &notes);
  // Two copies of the 69,451-triangle bunny and the ground: a quad split into 8 × 8 cells of
  // two triangles (scenes/scene_file.h).
  EXPECT_EQ(s.triangle_count(), 2u * 69451u + 8u * 8u * 2u);
  EXPECT_EQ(s.light.position, vec3(1, 4, 2));
  EXPECT_FLOAT_EQ(s.light.radius, 0.05f);
  EXPECT_EQ(s.camera.eye, vec3(0, 2, 5));
  EXPECT_FLOAT_EQ(s.camera.fov_y_deg, 50.0f);
}

}  // namespace
}  // namespace shadowlab
