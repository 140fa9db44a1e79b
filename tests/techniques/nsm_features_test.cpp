// The Neural Shadow Mapping features (techniques/nsm/nsm_features.h) against independent
// computations on the plane scene with one square occluder: a 1.2 m square at y = 1 under the
// light at (0, 2, 0), so a floor point p's ray to the light meets the occluder's plane at
// (p.x/2, 1, p.z/2) and z = |p − L|/2 there when that point lies on the square, else |p − L|.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/parallel.h"
#include "raster/gbuffer_pass.h"
#include "scenes/mesh_builders.h"
#include "scenes/scene_registry.h"
#include "techniques/nsm/nsm_features.h"

namespace shadowlab {
// A named namespace: the unity build compiles several test files in one translation unit.
namespace nsm_features_test {

constexpr int kRes = 256;     // base map face edge
constexpr float kHalf = 0.6f; // the occluder's half side

Scene occluder_scene() {
  Scene s = make_builtin_scene("plane");
  s.camera.width = 64;
  s.camera.height = 48;
  add_quad_mesh(s, vec3(-kHalf, 1, -kHalf), vec3(-kHalf, 1, kHalf), vec3(kHalf, 1, kHalf),
                vec3(kHalf, 1, -kHalf));
  s.light.radius = 0.15f;
  return s;
}

struct Fixture {
  Scene scene = occluder_scene();
  GBuffer g = render_gbuffer(scene);
  LightMap map;
  float scale = nsm_scene_scale(scene);
  NsmFeatures f;
  Fixture() {
    build_nsm_base_map(scene, g, kRes, map);
    f = compute_nsm_features(scene, g, kRes, map, scale, nsm_size_code(scene.light.radius),
                             nsm_feature_names());
  }
};

long double len(long double x, long double y, long double z) { return std::sqrt(x * x + y * y + z * z); }

TEST(NsmFeatures, ScaleAndSizeCode) {
  const Scene s = make_builtin_scene("default");
  EXPECT_NEAR(nsm_scene_scale(s), 1.0, 1e-3);  // the default scene defines s0 = 3.12 m
  EXPECT_NEAR(nsm_size_code(0.3f), 4.0, 1e-6);
  EXPECT_NEAR(nsm_size_code(0.15f), 2.0, 1e-6);
  EXPECT_NEAR(occluder_scene().light.position.y, 2.0, 0.0);
  EXPECT_NEAR(nsm_scene_scale(occluder_scene()), 2.0 / 3.12, 1e-6);
}

// d, z_f, c_e, c_c and the view normal from the GBuffer's points in long double; z from the
// analytic occluder within the nearest texel's reach: the texel centre's direction is at most
// half a texel diagonal, √2/res rad, off the pixel's, and along a plane at distance h from the
// light the radial distance z = h/cos θ changes by z·tan θ per radian.
TEST(NsmFeatures, MatchIndependentComputation) {
  const Fixture x;
  const long double s = x.scale, L[3] = {0, 2, 0};
  const Camera& cam = x.scene.camera;
  const long double eye[3] = {cam.eye.x, cam.eye.y, cam.eye.z};
  int floor_lit = 0, floor_shadowed = 0, occluder = 0;
  for (size_t i = 0; i < x.g.pixel_count(); ++i) {
    if (!x.g.covered[i]) continue;
    const vec3 p = x.g.position[i], n = x.g.geo_normal[i];
    ASSERT_NEAR(n.y, 1.0, 1e-6);  // every visible surface faces up, toward the eye
    const long double dl = len(L[0] - p.x, L[1] - p.y, L[2] - p.z);
    const long double de = len(eye[0] - p.x, eye[1] - p.y, eye[2] - p.z);
    const long double d = x.g.depth[i] / s, zf = dl / s;
    const long double ce = (L[1] - p.y) / dl, cc = (eye[1] - p.y) / de;
    EXPECT_NEAR(x.f.plane("d")[i], d, 1e-6 * d);
    EXPECT_NEAR(x.f.plane("z_f")[i], zf, 1e-6 * zf);
    EXPECT_NEAR(x.f.plane("c_e")[i], ce, 1e-6);
    EXPECT_NEAR(x.f.plane("c_c")[i], cc, 1e-6);
    EXPECT_NEAR(x.f.plane("c_e_r")[i], ce + 2.0L, 2e-6);
    // The camera looks straight down (up = −z): view space x = world x, y = −world z, z = world y.
    EXPECT_NEAR(x.f.plane("n_x")[i], 0.0, 1e-6);
    EXPECT_NEAR(x.f.plane("n_y")[i], 0.0, 1e-6);
    EXPECT_NEAR(x.f.plane("n_z")[i], 1.0, 1e-6);
    // z: which surface the light sees first along p − L.
    long double z_exp, h;
    if (std::fabs(p.y - 1.0f) < 1e-3f) {
      z_exp = dl;  // on the occluder: itself
      h = 1;
      ++occluder;
    } else {
      const long double hx = std::fabs(p.x / 2.0L), hz = std::fabs(p.z / 2.0L), m = std::max(hx, hz);
      if (std::fabs(m - kHalf) < 0.02L) continue;  // the nearest texel may see either surface
      if (m < kHalf) {
        z_exp = dl / 2;
        h = 1;
        ++floor_shadowed;
      } else {
        z_exp = dl;
        h = 2;
        ++floor_lit;
      }
    }
    const long double tan_t = std::sqrt(std::max(0.0L, z_exp * z_exp - h * h)) / h;
    const long double bound = (1.5L * z_exp * tan_t * std::sqrt(2.0L) / kRes + 1e-5L * z_exp) / s;
    EXPECT_NEAR(x.f.plane("z")[i], z_exp / s, bound) << "pixel " << i << " at " << p.x << "," << p.y << "," << p.z;
  }
  EXPECT_GT(floor_lit, 200);
  EXPECT_GT(floor_shadowed, 50);
  EXPECT_GT(occluder, 50);
}

// The derived features are formed from the fp32 planes: exact fp32 operations on them.
TEST(NsmFeatures, DerivedFromTheFp32Planes) {
  const Fixture x;
  const std::vector<float>&z = x.f.plane("z"), &zf = x.f.plane("z_f"), &cc = x.f.plane("c_c"),
                          &d = x.f.plane("d");
  for (size_t i = 0; i < x.g.pixel_count(); ++i) {
    if (!x.g.covered[i]) continue;
    EXPECT_EQ(x.f.plane("z_minus_zf")[i], z[i] - zf[i]);
    EXPECT_EQ(x.f.plane("z_over_zf")[i], z[i] / zf[i]);
    EXPECT_EQ(x.f.plane("cc_over_d")[i], cc[i] / d[i]);
  }
}

// Asking for a plane the features do not hold is a check failure (a programming error), named
// as such, not a read past the list of names.
TEST(NsmFeaturesDeathTest, AnUnknownPlaneIsACheckFailure) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const Fixture x;
  EXPECT_DEATH(x.f.plane("no_such_plane"), "CHECK\\(false\\)");
}

TEST(NsmFeatures, UncoveredPixelsAreZero) {
  const Fixture x;
  size_t uncovered = 0;
  for (size_t i = 0; i < x.g.pixel_count(); ++i) {
    EXPECT_EQ(x.f.coverage[i], x.g.covered[i]);
    if (x.g.covered[i]) continue;
    ++uncovered;
    for (const std::vector<float>& plane : x.f.planes) EXPECT_EQ(plane[i], 0.0f);
  }
  // 8 m up with a 60° fov the 4:3 view is 12.3 m wide over a 10 m floor: both sides are empty.
  EXPECT_GT(uncovered, 300u);
}

// An empty texel (the light saw nothing there, +inf) gives far. The floor fills every texel a
// pixel reads, so the test empties the rendered map: every covered pixel then reads +inf.
TEST(NsmFeatures, EmptyTexelIsFar) {
  Fixture x;
  for (size_t f = 0; f < x.map.dist.distance.size(); ++f)
    for (float& v : x.map.dist.distance[f]) v = std::numeric_limits<float>::infinity();
  const std::vector<float> z = nsm_map_distances(x.scene, x.g, kRes, x.map);
  for (size_t i = 0; i < x.g.pixel_count(); ++i)
    EXPECT_EQ(z[i], x.g.covered[i] ? x.scene.light.far : 0.0f);
}

TEST(NsmFeatures, SameBitsAt1_2_7Threads) {
  const int saved = thread_count();
  std::vector<std::vector<float>> first;
  for (int t : {1, 2, 7}) {
    set_thread_count(t);
    const Fixture x;
    if (first.empty()) {
      first = x.f.planes;
      continue;
    }
    ASSERT_EQ(x.f.planes.size(), first.size());
    for (size_t k = 0; k < first.size(); ++k)
      EXPECT_EQ(std::memcmp(x.f.planes[k].data(), first[k].data(), first[k].size() * 4), 0)
          << x.f.names[k] << " at " << t << " threads";
  }
  set_thread_count(saved);
}

}  // namespace nsm_features_test
}  // namespace shadowlab
