// Face layouts: the tetrahedron's geometry, the atlas size rule, and that rendering (the face's
// view-projection) and lookup (face_of + face_texel_coords) agree texel for texel.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "techniques/pipeline/cube_faces.h"
#include "techniques/pipeline/light_faces.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (;;) {
    const vec3 d(n(rng), n(rng), n(rng));
    if (glm::length(d) > 1e-3f) return glm::normalize(d);
  }
}

TEST(LightFaces, TetrahedronNormalsAre109DegreesApart) {
  vec3 sum(0.0f);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(glm::length(kTetraNormals[i]), 1.0f, 1e-6f);
    sum += kTetraNormals[i];
    for (int j = i + 1; j < 4; ++j)  // cos 109.47° = -1/3
      EXPECT_NEAR(glm::dot(kTetraNormals[i], kTetraNormals[j]), -1.0f / 3.0f, 1e-6f);
  }
  EXPECT_NEAR(glm::length(sum), 0.0f, 1e-6f);
}

// S is even and its texel count is the closest of all even sizes to 6·N² (Kluczek's rule).
TEST(LightFaces, AtlasTexelCountIsClosestToSixCubeFaces) {
  EXPECT_EQ(tetra_atlas_size(1024), 2508);  // √6 · 1024 = 2508.3
  EXPECT_EQ(tetra_atlas_size(128), 314);    // √6 · 128 = 313.5: |314² - 98304| = 292 < |312² - 98304| = 960
  for (int n = 1; n <= 3000; n += 7) {
    const int s = tetra_atlas_size(n);
    ASSERT_EQ(s % 2, 0);
    const double target = 6.0 * n * n;
    for (int other = std::max(2, s - 6); other <= s + 6; other += 2)
      ASSERT_LE(std::fabs(double(s) * s - target), std::fabs(double(other) * other - target))
          << "n " << n << " s " << s << " other " << other;
  }
}

// The owned spherical triangle's corners (the other faces' negated normals) sit at the tight
// box's corners/edges: (0, 2√2) and (±√6, -√2) in plane coordinates.
TEST(LightFaces, TetrahedronFaceBoxIsTightAroundItsTriangle) {
  const FaceLayout L = tetra_layout(256, 0);
  for (int i = 0; i < 4; ++i) {
    const LightFace& f = L.faces[size_t(i)];
    float umin = 1e9f, umax = -1e9f, vmin = 1e9f, vmax = -1e9f;
    for (int j = 0; j < 4; ++j) {
      if (j == i) continue;
      const vec3 c = -kTetraNormals[j];
      const float u = glm::dot(c, f.right) / glm::dot(c, f.forward);
      const float v = glm::dot(c, f.up) / glm::dot(c, f.forward);
      umin = std::min(umin, u), umax = test::worst_of(umax, u);
      vmin = std::min(vmin, v), vmax = test::worst_of(vmax, v);
    }
    EXPECT_NEAR(umin, -std::sqrt(6.0f), 1e-4f);
    EXPECT_NEAR(umax, std::sqrt(6.0f), 1e-4f);
    EXPECT_NEAR(vmin, -std::sqrt(2.0f), 1e-4f);
    EXPECT_NEAR(vmax, 2.0f * std::sqrt(2.0f), 1e-4f);
    EXPECT_NEAR(f.left, umin, 1e-4f);
    EXPECT_NEAR(f.top, vmax, 1e-4f);
    EXPECT_EQ(f.width, 628 / 2);  // S(256) = 628: 628² - 6·256² = 1168 < 6·256² - 626² = 1340
  }
}

// Every direction lands in its own face's owned region (inside the guard band), for both
// layouts; and the face's view-projection puts it at the same texel coordinates the lookup
// computes (render and lookup agree).
TEST(LightFaces, RenderAndLookupAgreeOnFaceAndTexel) {
  PointLight light;
  light.position = vec3(0.4f, -1.2f, 2.5f);
  light.near = 0.05f;
  light.far = 30.0f;
  std::mt19937 rng(11);
  for (const FaceLayout& L : {cube_layout(64, 3), tetra_layout(64, 3)}) {
    for (int i = 0; i < 20000; ++i) {
      const vec3 d = random_direction(rng);
      const int face = face_of(L, d);
      if (L.kind == FaceLayoutKind::Tetrahedron) {
        for (size_t k = 0; k < 4; ++k)  // argmax rule: no face is more aligned
          ASSERT_LE(glm::dot(d, kTetraNormals[k]), glm::dot(d, kTetraNormals[face]));
      }
      const LightFace& f = L.faces[size_t(face)];
      const vec2 st = face_texel_coords(f, d);
      const float g = float(L.guard) - 1e-3f;
      ASSERT_GE(st.x, g) << "dir " << i;
      ASSERT_GE(st.y, g);
      ASSERT_LE(st.x, float(f.width) - g);
      ASSERT_LE(st.y, float(f.height) - g);
      // The rasterizer's screen mapping: x = (ndc.x + 1)/2 · W, y = (1 - ndc.y)/2 · H.
      const vec4 q = face_view_proj(f, light) * vec4(light.position + 2.0f * d, 1.0f);
      const float sx = (q.x / q.w + 1.0f) * 0.5f * float(f.width);
      const float sy = (1.0f - q.y / q.w) * 0.5f * float(f.height);
      EXPECT_NEAR(sx, st.x, 2e-3f * float(f.width) / 64.0f);
      EXPECT_NEAR(sy, st.y, 2e-3f * float(f.height) / 64.0f);
      // The texel-centre direction maps back to its own coordinates.
      const vec3 back = face_texel_direction(f, st.x, st.y);
      EXPECT_NEAR(glm::dot(back, d), 1.0f, 1e-5f);
    }
  }
}

// With no guard, the generic cube face maps a direction exactly like cube_faces.h.
TEST(LightFaces, CubeLayoutMatchesCubeFaces) {
  const FaceLayout L = cube_layout(128, 0);
  std::mt19937 rng(5);
  for (int i = 0; i < 5000; ++i) {
    const vec3 d = random_direction(rng);
    const int face = face_of(L, d);
    ASSERT_EQ(face, cube_face_of(d));
    const vec2 uv = cube_face_uv(face, d);
    const vec2 st = face_texel_coords(L.faces[size_t(face)], d);
    EXPECT_NEAR(st.x, (uv.x * 0.5f + 0.5f) * 128.0f, 1e-3f);
    EXPECT_NEAR(st.y, (0.5f - uv.y * 0.5f) * 128.0f, 1e-3f);
  }
}

}  // namespace
}  // namespace shadowlab
