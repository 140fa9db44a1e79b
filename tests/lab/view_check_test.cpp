// The frustum test of lab/view_check.h against cameras placed by hand.
#include "lab/view_check.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadowlab {
namespace {

Bounds unit_box() {
  Bounds b;
  b.lo = vec3(-1.0f);
  b.hi = vec3(1.0f);
  return b;
}

Camera looking(vec3 eye, vec3 target) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.fov_y_deg = 60.0f;
  c.near = 0.05f;
  c.far = 100.0f;
  c.width = 64;
  c.height = 48;
  return c;
}

TEST(ViewCheck, FrustumAgainstTheBounds) {
  const Bounds b = unit_box();
  EXPECT_FALSE(bounds_outside_view(looking(vec3(0, 0, 5), vec3(0)), b));      // straight at it
  EXPECT_TRUE(bounds_outside_view(looking(vec3(0, 0, 5), vec3(0, 0, 10)), b));  // turned away
  EXPECT_TRUE(bounds_outside_view(looking(vec3(0, 0, 200), vec3(0)), b));     // beyond far
  EXPECT_TRUE(bounds_outside_view(looking(vec3(1e30f, 0, 0), vec3(0)), b));   // 1e30 m away
  EXPECT_FALSE(bounds_outside_view(looking(vec3(0), vec3(0, 0, -1)), b));     // inside the box
  // The side planes: half the vertical fov is 30°; a box centred 40° above the view axis at
  // 5 m lies beyond the top plane once its near corner does, at 20° it is seen.
  const auto above = [](double deg) {
    const float y = float(5.0 * std::tan(deg * M_PI / 180.0));
    return looking(vec3(0, -y, 5), vec3(0, -y, 0));
  };
  EXPECT_FALSE(bounds_outside_view(above(20.0), b));
  EXPECT_TRUE(bounds_outside_view(above(60.0), b));
  Bounds empty;
  EXPECT_TRUE(bounds_outside_view(looking(vec3(0, 0, 5), vec3(0)), empty));
}

// A point lying on a side plane is in view (the slack keeps it), on each of the four planes;
// one 1e-3 of its distance beyond the plane is outside. Camera at the origin looking down −z,
// fov 60° over 48 rows of 64: tan of the half angles 0.57735 (vertical) and 0.76980.
TEST(ViewCheck, PointsOnEachSidePlaneAreSeen) {
  const Camera c = looking(vec3(0), vec3(0, 0, -1));
  const double ty = std::tan(M_PI / 6.0), tx = ty * 64.0 / 48.0, z = 5.0;
  const vec3 on[4] = {vec3(float(z * tx), 0, float(-z)), vec3(float(-z * tx), 0, float(-z)),
                      vec3(0, float(z * ty), float(-z)), vec3(0, float(-z * ty), float(-z))};
  for (int k = 0; k < 4; ++k) {
    Bounds p;
    p.lo = p.hi = on[k];
    EXPECT_FALSE(bounds_outside_view(c, p)) << "plane " << k;
    p.lo = p.hi = on[k] * vec3(1.001f, 1.001f, 1.0f);
    EXPECT_TRUE(bounds_outside_view(c, p)) << "plane " << k;
  }
}

}  // namespace
}  // namespace shadowlab
