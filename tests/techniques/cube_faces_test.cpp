// Cube-face selection and face coordinates agree between rendering and lookup.
#include <gtest/gtest.h>

#include <random>

#include "techniques/pipeline/cube_faces.h"

namespace shadowlab {
namespace {

TEST(CubeFaces, MajorAxisWithFixedTieBreak) {
  EXPECT_EQ(cube_face_of({1, 0, 0}), 0);
  EXPECT_EQ(cube_face_of({-1, 0.5f, 0.5f}), 1);
  EXPECT_EQ(cube_face_of({0.2f, 3, -1}), 2);
  EXPECT_EQ(cube_face_of({0, -3, 1}), 3);
  EXPECT_EQ(cube_face_of({0, 0, 2}), 4);
  EXPECT_EQ(cube_face_of({0, 0, -2}), 5);
  // Ties: x before y before z.
  EXPECT_EQ(cube_face_of({1, 1, 1}), 0);
  EXPECT_EQ(cube_face_of({0, -1, -1}), 3);
}

TEST(CubeFaces, DirectionThroughFaceCoordinatesProjectsBack) {
  PointLight light;
  light.position = vec3(0.3f, -1.0f, 2.0f);
  const mat4 proj = cube_face_projection(light);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.999f, 0.999f);
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < 200; ++i) {
      const float a = u(rng), b = u(rng);
      const vec3 d = cube_face_direction(face, a, b);
      ASSERT_EQ(cube_face_of(d), face);
      const vec4 q = proj * cube_face_view(light, face) * vec4(light.position + 3.0f * d, 1.0f);
      EXPECT_NEAR(q.x / q.w, a, 1e-5f) << "face " << face;
      EXPECT_NEAR(q.y / q.w, b, 1e-5f) << "face " << face;
    }
}

}  // namespace
}  // namespace shadowlab
