// The dual-paraboloid vertex transform (raster/paraboloid.h) against its definition, evaluated
// in double: direction d̂ with z = d̂·forward maps to q = (d̂·right, d̂·up) / (1 + z); clip x and
// y are q mapped from the face's extent to [−1, 1], times w = |d|; z/w = 2(z + behind) /
// (1 + behind) − 1.
#include <gtest/gtest.h>

#include <cmath>

#include "raster/paraboloid.h"

namespace shadowlab {
namespace {

TEST(Paraboloid, ClipCoordinatesFollowTheDefinition) {
  ParaboloidProjection p;
  p.centre = vec3(0.5f, 2.0f, -1.0f);
  p.forward = vec3(0, -1, 0);
  p.right = vec3(1, 0, 0);
  p.up = vec3(0, 0, 1);
  // An extent that is not centred, so each of its four numbers matters.
  p.left = -1.1f;
  p.right_edge = 1.3f;
  p.bottom = -0.9f;
  p.top = 1.2f;
  p.behind = 0.4f;
  const vec3 dirs[] = {{0, -1, 0}, {1, 0, 0}, {0.3f, -0.8f, 0.5f}, {-0.6f, -0.2f, -0.7f}, {0.2f, 0.3f, 0.9f}};
  for (const vec3& dir : dirs)
    for (const float len : {0.25f, 3.0f}) {
      const vec3 d = glm::normalize(dir) * len;
      const vec4 c = paraboloid_clip(p, p.centre + d);
      const dvec3 u = glm::normalize(dvec3(d));
      const double z = glm::dot(u, dvec3(p.forward));
      const double qx = glm::dot(u, dvec3(p.right)) / (1.0 + z), qy = glm::dot(u, dvec3(p.up)) / (1.0 + z);
      const double nx = (qx - p.left) / (double(p.right_edge) - p.left) * 2.0 - 1.0;
      const double ny = (qy - p.bottom) / (double(p.top) - p.bottom) * 2.0 - 1.0;
      const double nz = 2.0 * (z + p.behind) / (1.0 + p.behind) - 1.0;
      const double w = glm::length(dvec3(d));
      EXPECT_NEAR(c.w, w, 1e-6 * w);
      EXPECT_NEAR(c.x / c.w, nx, 2e-6) << dir.x << "," << dir.y << "," << dir.z;
      EXPECT_NEAR(c.y / c.w, ny, 2e-6) << dir.x << "," << dir.y << "," << dir.z;
      EXPECT_NEAR(c.z / c.w, nz, 2e-6) << dir.x << "," << dir.y << "," << dir.z;
    }
}

}  // namespace
}  // namespace shadowlab
