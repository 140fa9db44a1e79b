// scene_mesh_views' per-mesh bounds (raster/pipeline.h), which the binner culls whole meshes
// by: computed in parallel chunks for large meshes, they must equal a brute-force min and max,
// and a non-finite position must never leave bounds that miss a finite one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/parallel.h"
#include "core/scene.h"
#include "raster/pipeline.h"

namespace shadowlab {
namespace {

Scene scene_of(std::vector<vec3> positions) {
  Scene s;
  Mesh m;
  m.positions = std::move(positions);
  m.indices = {0, 1, 2};
  s.meshes.push_back(std::move(m));
  return s;
}

std::vector<vec3> random_positions(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1000.0f, 1000.0f);
  std::vector<vec3> p(n);
  for (vec3& v : p) v = vec3(u(rng), u(rng), u(rng));
  return p;
}

TEST(MeshViews, BoundsAreTheBruteForceMinAndMaxAtAnySizeAndThreadCount) {
  // Sizes around the parallel grain (65,536 positions) and well past it.
  for (const size_t n : {size_t(1), size_t(1000), size_t(65536), size_t(65537), size_t(300001)}) {
    std::vector<vec3> pos = random_positions(n, uint32_t(n));
    // Extremes in the last chunk (whose length varies with n) and at the grain's edge.
    pos.back() = vec3(2000.0f, -2000.0f, 2000.0f);
    if (n > 65536) pos[65536] = vec3(-2000.0f, 2000.0f, -2000.0f);
    const Scene s = scene_of(pos);
    vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const vec3& p : s.meshes[0].positions)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], p[c]);
        hi[c] = std::max(hi[c], p[c]);
      }
    for (const int threads : {1, 2, 7}) {
      set_thread_count(threads);
      const std::vector<MeshView> v = scene_mesh_views(s);
      ASSERT_EQ(v.size(), 1u);
      ASSERT_TRUE(v[0].has_bounds) << n;
      EXPECT_EQ(v[0].lo, lo) << n << " positions, " << threads << " threads";
      EXPECT_EQ(v[0].hi, hi) << n << " positions, " << threads << " threads";
    }
  }
  set_thread_count(2);
}

TEST(MeshViews, NonFinitePositionsNeverLeaveBoundsThatMissAFinitePosition) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // A NaN first in the mesh, first in a later chunk, and inside a chunk; the extremes sit in
  // the chunk the NaN starts, where a combine that skipped the NaN chunk would lose them.
  for (const size_t at : {size_t(0), size_t(65536), size_t(131072), size_t(70000)}) {
    std::vector<vec3> p = random_positions(200000, 7);
    p[at + 1] = vec3(5000.0f, -5000.0f, 5000.0f);
    p[at + 2] = vec3(-5000.0f, 5000.0f, -5000.0f);
    p[at] = vec3(nan, 0.0f, 0.0f);
    const std::vector<MeshView> v = scene_mesh_views(scene_of(p));
    if (!v[0].has_bounds) continue;  // no bounds: nothing culled, always safe
    for (const vec3& q : p) {
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
      for (int c = 0; c < 3; ++c) {
        ASSERT_LE(v[0].lo[c], q[c]) << "NaN at " << at;
        ASSERT_GE(v[0].hi[c], q[c]) << "NaN at " << at;
      }
    }
  }
  // An infinite position: the bounds are dropped (as they always were).
  std::vector<vec3> p = random_positions(200000, 8);
  p[150000].y = inf;
  EXPECT_FALSE(scene_mesh_views(scene_of(p))[0].has_bounds);
}

}  // namespace
}  // namespace shadowlab
