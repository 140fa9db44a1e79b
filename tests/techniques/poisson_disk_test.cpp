// The Poisson-disk pattern of rotated Poisson PCF: n points inside the unit disk, spaced, and the
// same for every call.
#include "techniques/lookup/poisson_disk.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadowlab {
namespace {

TEST(PoissonDisk, PointsAreInsideTheDiskSpacedAndFixed) {
  for (const int n : {4, 8, 16, 32, 64}) {
    const PoissonDisk d = poisson_disk(n);
    ASSERT_EQ(int(d.points.size()), n);
    for (const vec2& p : d.points) EXPECT_LE(glm::dot(p, p), 1.0f) << n;
    // Spacing: measured min_distance·√n = 0.86-1.24 (n = 4..64); uniform random points of the
    // same count come far closer (their nearest pair is ~0.1/√n apart for n = 64).
    EXPECT_GE(d.min_distance * std::sqrt(float(n)), 0.5f) << n;
    RecordProperty("spacing_" + std::to_string(n), std::to_string(d.min_distance * std::sqrt(float(n))));
    const PoissonDisk again = poisson_disk(n);
    for (int i = 0; i < n; ++i) EXPECT_EQ(again.points[size_t(i)], d.points[size_t(i)]);
  }
}

// The rotation is a function of the pixel: fixed per pixel, spread over the circle across pixels
// (a constant angle would turn the noise back into banding).
TEST(PoissonDisk, RotationDependsOnThePixelOnly) {
  const int n = 4096;
  int quadrant[4] = {0, 0, 0, 0};
  double mean_c = 0.0, mean_s = 0.0;
  int same_as_next = 0;
  for (int i = 0; i < n; ++i) {
    const vec2 r = poisson_rotation(size_t(i));
    EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
    EXPECT_EQ(poisson_rotation(size_t(i)), r);
    same_as_next += poisson_rotation(size_t(i) + 1) == r;
    ++quadrant[(r.x >= 0.0f ? 0 : 1) + (r.y >= 0.0f ? 0 : 2)];
    mean_c += r.x / n;
    mean_s += r.y / n;
  }
  // Uniform angles: each quadrant holds n/4 ± a few σ (σ = √(n·3/16) ≈ 28), the mean vector ~0
  // (σ of each mean ≈ 0.011).
  for (const int q : quadrant) EXPECT_NEAR(q, n / 4, 100) << q;
  // One of 4096 angles per pixel: neighbours share one by chance about once in 4096 pairs
  // (measured 2); one angle per 8 pixels would share 7 of every 8.
  EXPECT_LE(same_as_next, 8);
  EXPECT_NEAR(mean_c, 0.0, 0.04);
  EXPECT_NEAR(mean_s, 0.0, 0.04);
}

}  // namespace
}  // namespace shadowlab
