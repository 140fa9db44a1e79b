// The box room's receivers (scenes/box_room.h): each lies on the 4 m box's wall that the
// light's ray through it meets first, its normal is that wall's inward normal, and only the
// points within 0.4 m of two walls at once are left out. Checked per direction from the
// geometry of a cube, not from the builder's loop.
#include <gtest/gtest.h>

#include <cmath>

#include "scenes/box_room.h"

namespace shadowlab {
namespace {

TEST(BoxRoom, ReceiversLieOnTheWallsFacingInward) {
  const BoxRoom b = make_box_room();
  const vec3 L = b.scene.light.position;
  ASSERT_EQ(b.g.width * b.g.height, 90000);
  size_t covered = 0;
  int per_wall[6] = {0, 0, 0, 0, 0, 0};
  for (size_t i = 0; i < b.g.covered.size(); ++i) {
    if (!b.g.covered[i]) continue;
    ++covered;
    const vec3 q = b.g.position[i], n = b.g.normal[i];
    // On the box's surface: the largest |coordinate| is 2, and no coordinate is beyond it.
    const float m = std::max({std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
    ASSERT_NEAR(m, 2.0f, 1e-5f) << i;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (std::fabs(q[a]) > std::fabs(q[axis])) axis = a;
    // The wall's inward normal: unit, along that axis, pointing back into the box (at the light).
    vec3 want(0.0f);
    want[axis] = q[axis] > 0.0f ? -1.0f : 1.0f;
    ASSERT_EQ(n, want) << i;
    ASSERT_EQ(b.g.geo_normal[i], want) << i;
    ASSERT_GT(glm::dot(n, L - q), 0.0f) << i;
    // Not within 0.4 m of a second wall.
    int near_edges = 0;
    for (int a = 0; a < 3; ++a) near_edges += std::fabs(q[a]) > 1.6f;
    ASSERT_EQ(near_edges, 1) << i;
    ++per_wall[2 * axis + (q[axis] > 0.0f)];
  }
  // Every wall holds receivers: the light is near the centre, so each wall takes roughly a
  // sixth of the directions (its solid angle from L), minus its rim.
  for (int w = 0; w < 6; ++w) EXPECT_GT(per_wall[w], 5000) << "wall " << w;
  // The kept part of a wall, its central 3.2 × 3.2 m square 2 m from the box's centre,
  // subtends 4·asin(1.6² / (1.6² + 2²)) = 1.604 sr from there: six of them are 76.6 % of the
  // sphere of directions (the light is 0.37 m off centre; measured 76.6 %).
  EXPECT_GT(covered, 90000 * 0.74);
  EXPECT_LT(covered, 90000 * 0.79);
}

}  // namespace
}  // namespace shadowlab
