// Cube-face selection and face coordinates agree between rendering and lookup.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
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

// The written-out right axes are forward × up, computed here by glm, bit for bit (signed zeros
// too), and each face's three axes are an orthonormal right-handed frame (right × up = −forward:
// the view looks down −z).
TEST(CubeFaces, RightIsForwardCrossUpBitForBit) {
  for (int face = 0; face < kCubeFaces; ++face) {
    const vec3 want = glm::cross(kCubeForward[face], kCubeUp[face]);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(std::bit_cast<uint32_t>(kCubeRight[face][c]), std::bit_cast<uint32_t>(want[c]))
          << "face " << face << " component " << c;
    EXPECT_EQ(glm::cross(kCubeRight[face], kCubeUp[face]), -kCubeForward[face]) << face;
  }
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
