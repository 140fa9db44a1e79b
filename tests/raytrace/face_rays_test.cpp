// face_rays / perspective_rays on analytic scenes: the rays through texel centres of a
// perspective view hit what geometry says, at the view depth along the view's −z axis.
#include "raytrace/face_rays.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/parallel.h"
#include "scenes/scene_library.h"
#include "raytrace/embree_scene.h"

namespace shadowlab {
namespace {

// Cube-face views of a light: forward (view −z) and up per face, in the order +X −X +Y −Y +Z −Z.
mat4 face_view(vec3 light, int face) {
  static const vec3 kForward[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                   {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  static const vec3 kUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                              {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  return glm::lookAtRH(light, light + kForward[face], kUp[face]);
}

TEST(FaceRays, PlaneSeenFromTheLightHasAnalyticDepth) {
  // The "plane" scene: a 10 × 10 m floor at y = 0 (x, z in [−5, 5]) and the light 2 m above
  // its centre. 90° faces of 64 × 64 texels, NDC (u, v) of texel (x, y) = ((2x + 1)/64 − 1,
  // 1 − (2y + 1)/64).
  //  - Face −Y (looking down): every texel ray meets the floor at view depth 2 (the face's
  //    footprint is the 4 × 4 m square under the light).
  //  - Face +Y (looking up): nothing.
  //  - Face +X (forward +x, up −y, so right = forward × up = (0, 0, −1)): texel (u, v) has the
  //    world direction (1, −v, −u) per unit view depth, which goes down for v > 0 and meets
  //    y = 0 at depth t = 2/v, at x = t, z = −u·t: a hit iff t <= 5 and |u|·t <= 5.
  const Scene scene = make_builtin_scene("plane");
  EmbreeScene rt(scene);
  const vec3 L = scene.light.position;
  const mat4 proj = glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, 0.05f, 20.0f);
  const int res = 64;

  const PrimaryHits down = face_rays(rt, face_view(L, 3), proj, res);
  ASSERT_EQ(down.width, res);
  ASSERT_EQ(down.height, res);
  for (size_t i = 0; i < down.depth.size(); ++i) {
    ASSERT_EQ(down.mesh_id[i], 0u) << "texel " << i;
    ASSERT_NE(down.prim_id[i], kNoPrimitive);
    ASSERT_NEAR(down.depth[i], 2.0f, 2e-6f) << "texel " << i;
  }

  const PrimaryHits up = face_rays(rt, face_view(L, 2), proj, res);
  for (size_t i = 0; i < up.depth.size(); ++i) {
    ASSERT_EQ(up.mesh_id[i], kNoPrimitive);
    ASSERT_EQ(up.prim_id[i], kNoPrimitive);
    ASSERT_TRUE(std::isinf(up.depth[i]));
  }

  const PrimaryHits side = face_rays(rt, face_view(L, 0), proj, res);
  size_t hits = 0;
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      const size_t i = size_t(y) * res + size_t(x);
      const double u = (2.0 * x + 1.0) / res - 1.0, v = 1.0 - (2.0 * y + 1.0) / res;
      const double t = v > 0.0 ? 2.0 / v : INFINITY;
      // Texels whose hit is within 1e-3 m of the floor's edge could go either way.
      const double margin = std::min(std::fabs(t - 5.0), std::fabs(std::fabs(u) * t - 5.0));
      if (margin < 1e-3) continue;
      const bool hit = t <= 5.0 && std::fabs(u) * t <= 5.0;
      ASSERT_EQ(side.mesh_id[i] != kNoPrimitive, hit) << "texel " << x << "," << y;
      if (hit) {
        ++hits;
        ASSERT_NEAR(side.depth[i], t, 1e-5 * t) << "texel " << x << "," << y;
      }
    }
  EXPECT_GT(hits, size_t(res * res / 8));
}

TEST(FaceRays, NearPlaneAndMaxDepthBoundTheHits) {
  // Looking down at the floor from 2 m: with max_depth 1.5 the floor (depth 2) is out of range;
  // with a projection whose near plane is at 2.5 m, too. Near 1.5 and max 2.5: hit.
  const Scene scene = make_builtin_scene("plane");
  EmbreeScene rt(scene);
  const mat4 view = face_view(scene.light.position, 3);
  const auto perspective = [](float n) {
    return glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, n, 20.0f);
  };
  for (uint32_t m : face_rays(rt, view, perspective(0.05f), 8, 1.5f).mesh_id)
    EXPECT_EQ(m, kNoPrimitive);
  for (uint32_t m : face_rays(rt, view, perspective(2.5f), 8).mesh_id) EXPECT_EQ(m, kNoPrimitive);
  for (uint32_t m : face_rays(rt, view, perspective(1.5f), 8, 2.5f).mesh_id) EXPECT_EQ(m, 0u);
}

TEST(FaceRays, PerspectiveRaysAgreeWithPrimaryVisibility) {
  // The same camera through both functions: identical primitives; depths agree to float
  // rounding of the two ways of building the ray direction.
  Scene scene = make_builtin_scene("default");
  scene.camera.width = 96;
  scene.camera.height = 72;
  EmbreeScene rt(scene);
  const PrimaryHits a = primary_visibility(rt, scene.camera);
  const PrimaryHits b =
      perspective_rays(rt, camera_view(scene.camera), camera_projection(scene.camera),
                       scene.camera.width, scene.camera.height, scene.camera.far);
  size_t same = 0;
  for (size_t i = 0; i < a.depth.size(); ++i) {
    if (a.mesh_id[i] == b.mesh_id[i] && a.prim_id[i] == b.prim_id[i]) ++same;
    if (a.mesh_id[i] != kNoPrimitive && b.mesh_id[i] == a.mesh_id[i]) {
      EXPECT_NEAR(a.depth[i], b.depth[i], 1e-5f * a.depth[i]) << "pixel " << i;
    }
  }
  EXPECT_GE(double(same), 0.999 * double(a.depth.size()));
}

TEST(FaceRays, IdenticalForAnyThreadCount) {
  const Scene scene = make_builtin_scene("default");
  EmbreeScene rt(scene);
  const mat4 proj = glm::perspectiveRH_NO(glm::radians(90.0f), 1.0f, 0.05f, 20.0f);
  std::vector<PrimaryHits> runs;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    runs.push_back(face_rays(rt, face_view(scene.light.position, 1), proj, 96));
  }
  set_thread_count(2);
  for (size_t r = 1; r < runs.size(); ++r) {
    EXPECT_EQ(runs[r].mesh_id, runs[0].mesh_id);
    EXPECT_EQ(runs[r].prim_id, runs[0].prim_id);
    EXPECT_EQ(0, std::memcmp(runs[r].depth.data(), runs[0].depth.data(), runs[0].depth.size() * 4));
  }
}

}  // namespace
}  // namespace shadowlab
