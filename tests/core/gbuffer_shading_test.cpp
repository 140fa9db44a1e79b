// The deferred shading attributes (core/gbuffer_shading.h): barycentric coordinates of a point
// against ones chosen in advance, and a GBuffer's own attributes passed through. The camera
// pass's pixels against closed forms: tests/raster/gbuffer_shading_pass_test.cpp.
#include <gtest/gtest.h>

#include <random>

#include "core/gbuffer_shading.h"

namespace shadowlab {
namespace {

// Points built from chosen barycentrics (in long double, rounded to float) get them back, in
// the plane and lifted off it along the normal (the projection's); a degenerate triangle gets
// the centroid.
TEST(GBufferShading, BarycentricsOfAPointAreTheChosenOnes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f), w(0.0f, 1.0f);
  double worst = 0.0;
  int tested = 0;
  for (int k = 0; k < 2000; ++k) {
    const vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const dvec3 n = glm::cross(dvec3(b) - dvec3(a), dvec3(c) - dvec3(a));
    // Well-shaped triangles only: the rounding of p to float moves l by |Δp| / height.
    const double area2 = glm::length(n);
    const double longest = std::max({glm::length(dvec3(b) - dvec3(a)),
                                     glm::length(dvec3(c) - dvec3(a)),
                                     glm::length(dvec3(c) - dvec3(b))});
    if (area2 / (longest * longest) < 0.2) continue;
    long double l1 = w(rng), l2 = w(rng);
    if (l1 + l2 > 1.0L) l1 = 1.0L - l1, l2 = 1.0L - l2;
    const long double l0 = 1.0L - l1 - l2;
    const double lift = k % 2 ? 0.0 : double(u(rng));
    vec3 p;
    for (int i = 0; i < 3; ++i)
      p[i] = float(l0 * a[i] + l1 * b[i] + l2 * c[i] + lift * (n[i] / area2));
    const dvec3 l = barycentric_of_point(p, a, b, c);
    EXPECT_NEAR(l.x + l.y + l.z, 1.0, 1e-12);
    worst = std::max({worst, std::fabs(l.x - double(l0)), std::fabs(l.y - double(l1)),
                      std::fabs(l.z - double(l2))});
    ++tested;
  }
  ASSERT_GT(tested, 500);
  // Measured 1.5e-6 (float rounding of p, |p| up to ~5, heights from ~0.5).
  EXPECT_LT(worst, 5e-6);
  const dvec3 centroid = barycentric_of_point(vec3(1, 2, 3), vec3(0), vec3(1, 1, 1), vec3(2, 2, 2));
  EXPECT_EQ(centroid, dvec3(1.0 / 3.0));
}

TEST(GBufferShading, AGBuffersOwnAttributesArePassedThrough) {
  Scene scene;  // never read: the GBuffer has its attributes
  GBuffer g;
  g.resize(3, 2);
  ASSERT_TRUE(g.has_shading_attributes());
  g.normal[4] = vec3(0, 0, 1);
  g.uv[4] = vec2(0.25f, 0.5f);
  const ShadingAttributes a = shading_attributes(scene, g, 4);
  EXPECT_EQ(a.normal, vec3(0, 0, 1));
  EXPECT_EQ(a.uv, vec2(0.25f, 0.5f));
  // Without them, an uncovered pixel has none.
  g.normal.clear();
  g.uv.clear();
  const ShadingAttributes e = shading_attributes(scene, g, 4);
  EXPECT_EQ(e.normal, vec3(0.0f));
  EXPECT_EQ(e.uv, vec2(0.0f));
}

}  // namespace
}  // namespace shadowlab
