// The Poisson-disk pattern of rotated Poisson PCF: n points inside the unit disk, spaced, and the
// same for every call.
#include "techniques/poisson_disk.h"

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

}  // namespace
}  // namespace shadowlab
