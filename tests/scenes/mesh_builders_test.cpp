#include "scenes/mesh_builders.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadowlab {
namespace {

// Every vertex normal lies on the front side of each triangle that uses it.
void expect_normals_on_front(const Mesh& m) {
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    const vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
               c = m.positions[m.indices[i + 2]];
    const vec3 g = glm::cross(b - a, c - a);
    ASSERT_GT(glm::length(g), 0.0f) << "degenerate triangle " << i / 3;
    for (int k = 0; k < 3; ++k)
      EXPECT_GT(glm::dot(m.normals[m.indices[i + size_t(k)]], g), 0.0f) << "triangle " << i / 3;
  }
}

TEST(MeshBuildersDeathTest, ASphereOrCylinderOfNoSizeIsAProgrammerError) {
  Mesh m;
  EXPECT_DEATH(add_uv_sphere(m, vec3(0.0f), 0.0f, 8, 4), "CHECK");
  EXPECT_DEATH(add_uv_sphere(m, vec3(0.0f), 1.0f, 2, 4), "CHECK");
  EXPECT_DEATH(add_uv_sphere(m, vec3(0.0f), 1.0f, 8, 1), "CHECK");
}

TEST(MeshBuilders, GridQuadFacesCrossOfEdges) {
  Mesh m;
  add_grid_quad(m, vec3(0), vec3(2, 0, 0), vec3(0, 0, -3), 4, 3);  // cross = (0, 6, 0): +y
  EXPECT_EQ(m.positions.size(), 5u * 4u);
  EXPECT_EQ(m.triangle_count(), 2u * 4u * 3u);
  for (const vec3& n : m.normals) EXPECT_EQ(n, vec3(0, 1, 0));
  expect_normals_on_front(m);
}

// A quad a, b, c, d: two triangles that cover it (their areas sum to the quad's, 2 × 3 m²),
// both facing the side it is counter-clockwise from (+y), with its material and uvs.
TEST(MeshBuilders, QuadMeshCoversItsQuadFacingItsFront) {
  Scene s;
  s.materials.resize(2);
  const int index = add_quad_mesh(s, vec3(0, 0, 0), vec3(0, 0, 3), vec3(2, 0, 3), vec3(2, 0, 0), 1,
                                  {vec2(0, 0), vec2(0, 1), vec2(1, 1), vec2(1, 0)});
  ASSERT_EQ(index, 0);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.name, "quad0");
  EXPECT_EQ(m.material, 1);
  ASSERT_EQ(m.triangle_count(), 2u);
  ASSERT_EQ(m.uvs.size(), 4u);
  double area = 0.0;
  for (size_t t = 0; t < 2; ++t) {
    const vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
               c = m.positions[m.indices[3 * t + 2]];
    area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
  }
  EXPECT_NEAR(area, 6.0, 1e-6);
  for (const vec3& n : m.normals) EXPECT_EQ(n, vec3(0, 1, 0));
  expect_normals_on_front(m);
}

TEST(MeshBuilders, BoxIsClosedOutwardWithFlatNormals) {
  Mesh m;
  add_box(m, glm::scale(glm::translate(mat4(1.0f), vec3(1, 2, 3)), vec3(2, 3, 4)));
  EXPECT_EQ(m.positions.size(), 24u);
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_NEAR(signed_volume(m), 24.0, 1e-4);
  expect_normals_on_front(m);
}

TEST(MeshBuilders, SphereIsOutwardWithRadialNormals) {
  Mesh m;
  const vec3 c(1, -2, 0.5f);
  add_uv_sphere(m, c, 0.5f, 32, 16);
  EXPECT_EQ(m.triangle_count(), 2u * 32u * 15u);
  const double exact = 4.0 / 3.0 * M_PI * 0.125;
  EXPECT_GT(signed_volume(m), 0.95 * exact);
  EXPECT_LT(signed_volume(m), exact);
  for (size_t i = 0; i < m.positions.size(); ++i)
    EXPECT_NEAR(glm::length(m.normals[i] - (m.positions[i] - c) / 0.5f), 0.0f, 1e-5f);
  expect_normals_on_front(m);
  // The coarsest sphere the builder takes: 3 segments, 2 rings (a triangular bipyramid).
  Mesh coarse;
  add_uv_sphere(coarse, c, 0.5f, 3, 2);
  EXPECT_EQ(coarse.triangle_count(), 2u * 3u * 1u);
}

TEST(MeshBuilders, CylinderIsClosedAndOutward) {
  Mesh m;
  add_cylinder(m, vec3(0, 1, 0), 0.1f, 2.0f, 16);
  EXPECT_EQ(m.triangle_count(), 4u * 16u);
  const double prism = 0.5 * 16 * 0.01 * std::sin(2 * M_PI / 16) * 2.0;  // inscribed 16-gon
  EXPECT_NEAR(signed_volume(m), prism, 1e-5);
  expect_normals_on_front(m);
}

}  // namespace
}  // namespace shadowlab
