// Hard and soft visibility on hand-built scenes with hand-filled GBuffers (no rasterizer).
#include "raytrace/visibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <thread>

#include "core/parallel.h"
#include "core/rng.h"
#include "raytrace/embree_scene.h"
#include "scenes/mesh_builders.h"

namespace shadowlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The quad a, b, c, d (counter-clockwise from its front) as one mesh (scenes/mesh_builders.h).
int add_test_quad(Scene& scene, vec3 a, vec3 b, vec3 c, vec3 d, int material = 0,
                  std::vector<vec2> uvs = {}) {
  return add_quad_mesh(scene, a, b, c, d, material, std::move(uvs));
}

// Horizontal quad at height y over [x0, x1] × [z0, z1], front face up.
int add_horizontal(Scene& scene, float y, float x0, float x1, float z0, float z1,
                   int material = 0, std::vector<vec2> uvs = {}) {
  return add_test_quad(scene, vec3(x0, y, z1), vec3(x1, y, z1), vec3(x1, y, z0), vec3(x0, y, z0),
                       material, std::move(uvs));
}

// Floor y = 0 over [-10, 10]², one opaque material, light above the origin.
Scene floor_scene(float light_height = 4.0f, float radius = 0.0f) {
  Scene s;
  s.name = "floor";
  s.materials.push_back(Material{});
  add_horizontal(s, 0.0f, -10.0f, 10.0f, -10.0f, 10.0f);
  s.light.position = vec3(0.0f, light_height, 0.0f);
  s.light.radius = radius;
  return s;
}

// A GBuffer of `points` (one per pixel, row-major, w wide) all covered, normal +y.
GBuffer gbuffer_of(const std::vector<vec3>& points, int w, vec3 normal = vec3(0, 1, 0)) {
  GBuffer g;
  const int h = int(points.size()) / w;
  g.resize(w, h);
  for (size_t i = 0; i < points.size(); ++i) {
    g.position[i] = points[i];
    g.normal[i] = normal;
    g.geo_normal[i] = normal;
    g.covered[i] = 1;
    g.mesh_id[i] = 0;
    g.prim_id[i] = 0;
  }
  return g;
}

// W × H points of the floor over [-2, 2]², pixel (x, y) at x-coordinate left to right.
GBuffer floor_gbuffer(int w, int h) {
  std::vector<vec3> pts;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      pts.push_back(vec3(-2.0f + 4.0f * (x + 0.5f) / w, 0.0f, -2.0f + 4.0f * (y + 0.5f) / h));
  return gbuffer_of(pts, w);
}

void expect_all(const ImageF& mask, float value, const char* what) {
  for (size_t i = 0; i < mask.data.size(); ++i)
    ASSERT_EQ(mask.data[i], value) << what << ", pixel " << i;
}

// Fraction of the cone of directions from p toward the sphere (c, r), uniform in solid angle,
// for which `blocked(dir)` holds — brute-force midpoint integration over (θ, φ) with the sinθ
// Jacobian, independent of the code's (1 − cosθ, φ) sampling.
double cone_fraction(vec3 p, vec3 c, double r, const std::function<bool(const dvec3&)>& blocked) {
  const dvec3 axis = glm::normalize(dvec3(c) - dvec3(p));
  const double theta_max = std::asin(r / glm::length(dvec3(c) - dvec3(p)));
  const dvec3 helper = std::abs(axis.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
  const dvec3 t1 = glm::normalize(glm::cross(helper, axis));
  const dvec3 t2 = glm::cross(axis, t1);
  const int nt = 1500, np = 1500;
  double total = 0.0, hit = 0.0;
  for (int i = 0; i < nt; ++i) {
    const double th = theta_max * (i + 0.5) / nt;
    const double wgt = std::sin(th);
    for (int j = 0; j < np; ++j) {
      const double ph = 2.0 * kPi * (j + 0.5) / np;
      const dvec3 d = axis * std::cos(th) + std::sin(th) * (std::cos(ph) * t1 + std::sin(ph) * t2);
      total += wgt;
      if (blocked(d)) hit += wgt;
    }
  }
  return hit / total;
}

TEST(HardVisibility, UnoccludedPlaneIsFullyLit) {
  const Scene s = floor_scene();
  const EmbreeScene rt(s);
  const GBuffer g = floor_gbuffer(16, 12);
  expect_all(hard_visibility(rt, s, g), 1.0f, "hard");
}

TEST(SoftVisibility, UnoccludedPlaneIsFullyLit) {
  const Scene s = floor_scene(4.0f, 0.5f);
  const EmbreeScene rt(s);
  const GBuffer g = floor_gbuffer(16, 12);
  expect_all(soft_visibility(rt, s, g, 16, 7), 1.0f, "soft");
}

TEST(HardVisibility, LargeOccluderBlocksEverything) {
  Scene s = floor_scene();
  add_horizontal(s, 2.0f, -5.0f, 5.0f, -5.0f, 5.0f);
  const EmbreeScene rt(s);
  const GBuffer g = floor_gbuffer(16, 12);
  expect_all(hard_visibility(rt, s, g), 0.0f, "hard");
}

TEST(SoftVisibility, LargeOccluderWithSmallLightBlocksEverything) {
  // The cone from any floor point in [-2,2]² toward a 0.1 m light at height 4 crosses y = 2
  // within 2.1 m of the origin, well inside the [-5,5]² occluder.
  Scene s = floor_scene(4.0f, 0.1f);
  add_horizontal(s, 2.0f, -5.0f, 5.0f, -5.0f, 5.0f);
  const EmbreeScene rt(s);
  const GBuffer g = floor_gbuffer(16, 12);
  expect_all(soft_visibility(rt, s, g, 16, 3), 0.0f, "soft");
}

TEST(Visibility, FacingAwayIsDarkAndUncoveredIsLit) {
  Scene s = floor_scene(4.0f, 0.3f);
  add_horizontal(s, 2.0f, -5.0f, 5.0f, -5.0f, 5.0f);  // occluder: must not matter for either
  const EmbreeScene rt(s);
  GBuffer g = floor_gbuffer(8, 8);
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (i % 2 == 0) {
      g.covered[i] = 0;  // uncovered → 1 (its stale position/normal must be ignored)
    } else {
      g.geo_normal[i] = vec3(0, -1, 0);  // facing away → 0 even though...
    }
  }
  // ...and with the occluder gone, facing-away pixels stay 0.
  Scene open = floor_scene(4.0f, 0.3f);
  const EmbreeScene rt_open(open);
  for (const ImageF& m : {hard_visibility(rt, s, g), soft_visibility(rt, s, g, 8, 1),
                          hard_visibility(rt_open, open, g), soft_visibility(rt_open, open, g, 8, 1)})
    for (size_t i = 0; i < m.data.size(); ++i)
      ASSERT_EQ(m.data[i], i % 2 == 0 ? 1.0f : 0.0f) << "pixel " << i;
  // A normal exactly perpendicular to the light direction is facing away (N·L <= 0).
  GBuffer grazing = gbuffer_of({vec3(0.0f, 0.0f, 0.0f)}, 1, vec3(1, 0, 0));
  EXPECT_EQ(hard_visibility(rt_open, open, grazing).data[0], 0.0f);
}

TEST(SoftVisibility, HalfPlaneEdgeThroughLightCentreGivesHalf) {
  // Occluder: half-plane y = 2, x < 0. Receivers at x = 0 on the floor; the line from each to the
  // light centre (0, 4, 0) lies in the plane x = 0 and so meets the occluder's edge. A direction
  // is blocked iff dir.x < 0, which splits the cone into two mirror halves: visibility 1/2.
  // Every 1-D stratum of φ holds one sample and the blocked set is a half-turn of φ, so at most
  // the two strata containing its ends miss their share: |v − 1/2| < 2/spp exactly.
  Scene s = floor_scene(4.0f, 0.5f);
  add_horizontal(s, 2.0f, -20.0f, 0.0f, -20.0f, 20.0f);
  const EmbreeScene rt(s);
  std::vector<vec3> pts;
  for (int i = 0; i < 32; ++i) pts.push_back(vec3(0.0f, 0.0f, -1.5f + 3.0f * i / 31.0f));
  const GBuffer g = gbuffer_of(pts, 8);
  for (int spp : {64, 7, 12, 100}) {
    const ImageF m = soft_visibility(rt, s, g, spp, 42);
    for (size_t i = 0; i < m.data.size(); ++i)
      EXPECT_LT(std::abs(m.data[i] - 0.5f), 2.0f / spp + 1e-6f) << "spp " << spp << " pixel " << i;
  }
}

TEST(SoftVisibility, OccluderBlocksNoneOrAllOfTheSphere) {
  // Same half-plane. From (3, 0, z) the cone toward the light (half-angle asin(0.5/5) ≈ 5.7°)
  // crosses y = 2 within 0.3 m of x = 1.5 (> 0): nothing blocked → 1. From (−3, 0, z) it crosses
  // around x = −1.5, entirely inside the half-plane → 0.
  Scene s = floor_scene(4.0f, 0.5f);
  add_horizontal(s, 2.0f, -20.0f, 0.0f, -20.0f, 20.0f);
  const EmbreeScene rt(s);
  std::vector<vec3> pts;
  for (int i = 0; i < 8; ++i) pts.push_back(vec3(3.0f, 0.0f, -1.0f + 0.25f * i));
  for (int i = 0; i < 8; ++i) pts.push_back(vec3(-3.0f, 0.0f, -1.0f + 0.25f * i));
  const GBuffer g = gbuffer_of(pts, 8);
  const ImageF m = soft_visibility(rt, s, g, 64, 5);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(m.data[size_t(i)], i < 8 ? 1.0f : 0.0f) << "pixel " << i;
}

TEST(SoftVisibility, OffAxisEdgeMatchesBruteForceSolidAngle) {
  // Receiver at (0.3, 0, 0), same half-plane: about a fifth of the cone is blocked. Expected value
  // from brute-force integration over the cone; 64 pixels share the point with independent
  // jitter, so their mean has a standard error below 0.5/√(64·spp) even without stratification.
  Scene s = floor_scene(4.0f, 0.5f);
  add_horizontal(s, 2.0f, -20.0f, 0.0f, -20.0f, 20.0f);
  const EmbreeScene rt(s);
  const vec3 p(0.3f, 0.0f, 0.0f);
  const double expected = cone_fraction(p, s.light.position, 0.5, [&](const dvec3& d) {
    const double t = 2.0 / d.y;  // where the ray reaches y = 2
    return d.y > 0 && p.x + t * d.x < 0.0;
  });
  ASSERT_GT(expected, 0.05);
  ASSERT_LT(expected, 0.5);
  const int spp = 64;
  const GBuffer g = gbuffer_of(std::vector<vec3>(64, p), 8);
  const ImageF m = soft_visibility(rt, s, g, spp, 11);
  double mean = 0.0;
  for (float v : m.data) mean += v;
  mean /= double(m.data.size());
  EXPECT_NEAR(mean, 1.0 - expected, 4.0 * 0.5 / std::sqrt(64.0 * spp)) << "expected blocked " << expected;
}

TEST(SoftVisibility, DirectionsBelowTheTangentPlaneAreBlocked) {
  // A wall point (normal +x) at the origin, no geometry at all; the light centre sits only
  // 0.25 m in front of the wall plane at 5 m distance, radius 0.5: the part of the cone with
  // dir.x <= 0 is behind the receiver and counts as blocked.
  Scene s;
  s.materials.push_back(Material{});
  s.light.position = vec3(0.25f, 0.0f, 5.0f);
  s.light.radius = 0.5f;
  const EmbreeScene rt(s);
  const vec3 p(0.0f);
  const double below = cone_fraction(p, s.light.position, 0.5, [](const dvec3& d) { return d.x <= 0.0; });
  ASSERT_GT(below, 0.1);
  const int spp = 64;
  const GBuffer g = gbuffer_of(std::vector<vec3>(64, p), 8, vec3(1, 0, 0));
  const ImageF m = soft_visibility(rt, s, g, spp, 2);
  double mean = 0.0;
  for (float v : m.data) mean += v;
  mean /= double(m.data.size());
  EXPECT_NEAR(mean, 1.0 - below, 4.0 * 0.5 / std::sqrt(64.0 * spp)) << "expected below " << below;
}

TEST(SoftVisibility, PointInsideTheLightIsLit) {
  Scene s = floor_scene(0.2f, 0.5f);  // sphere reaches below the floor point
  add_horizontal(s, 0.1f, -0.05f, 0.05f, -0.05f, 0.05f);  // a tiny occluder inside the light
  const EmbreeScene rt(s);
  const GBuffer g = gbuffer_of({vec3(0.0f, 0.0f, 0.0f)}, 1);
  EXPECT_EQ(soft_visibility(rt, s, g, 16, 1).data[0], 1.0f);
}

TEST(SoftVisibility, ZeroRadiusEqualsHard) {
  Scene s = floor_scene(4.0f, 0.0f);
  add_horizontal(s, 2.0f, -20.0f, 0.0f, -20.0f, 20.0f);
  const EmbreeScene rt(s);
  const GBuffer g = floor_gbuffer(16, 16);
  const ImageF hard = hard_visibility(rt, s, g);
  const ImageF soft = soft_visibility(rt, s, g, 32, 9);
  ASSERT_EQ(hard.data.size(), soft.data.size());
  EXPECT_EQ(0, std::memcmp(hard.data.data(), soft.data.data(), hard.data.size() * sizeof(float)));
  // Points with x < 0 are under the half-plane as seen from the light (the ray meets y = 2 at
  // x/2), points with x > 0 are lit.
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) EXPECT_EQ(hard.at(x, y), x < 8 ? 0.0f : 1.0f) << x << "," << y;
}

TEST(SoftVisibility, RejectsNonPositiveSpp) {
  const Scene s = floor_scene(4.0f, 0.5f);
  const EmbreeScene rt(s);
  const GBuffer g = floor_gbuffer(2, 2);
  EXPECT_THROW(soft_visibility(rt, s, g, 0, 1), InputError);
}

TEST(SoftVisibility, IdenticalBytesFor1And2And7Threads) {
  // Penumbrae of several occluders at different heights under a large light.
  Scene s = floor_scene(5.0f, 1.0f);
  add_horizontal(s, 1.0f, -1.5f, -0.5f, -1.0f, 1.0f);
  add_horizontal(s, 2.5f, 0.2f, 1.2f, -1.5f, 0.0f);
  add_test_quad(s, vec3(0.5f, 0.0f, 1.0f), vec3(1.5f, 0.0f, 1.0f), vec3(1.5f, 1.5f, 1.2f),
           vec3(0.5f, 1.5f, 1.2f));
  const EmbreeScene rt(s);
  const GBuffer g = floor_gbuffer(61, 37);  // not a multiple of the tile size
  std::vector<ImageF> masks;
  for (int threads : {1, 2, 7}) {
    set_thread_count(threads);
    masks.push_back(soft_visibility(rt, s, g, 24, 1234));
  }
  set_thread_count(int(std::max(1u, std::thread::hardware_concurrency())));
  int fractional = 0;
  for (float v : masks[0].data) fractional += (v > 0.0f && v < 1.0f);
  EXPECT_GT(fractional, 100) << "the scene should have penumbrae";
  for (size_t k = 1; k < masks.size(); ++k)
    EXPECT_EQ(0, std::memcmp(masks[0].data.data(), masks[k].data.data(),
                             masks[0].data.size() * sizeof(float)))
        << "run " << k;
  // A different seed changes the noise.
  const ImageF other = soft_visibility(rt, s, g, 24, 1235);
  EXPECT_NE(0, std::memcmp(masks[0].data.data(), other.data.data(), other.data.size() * sizeof(float)));
}

TEST(HardVisibility, ShadowRayNeverHitsItsOwnTriangle) {
  // Seeded property: random triangles of sizes 1 cm .. 100 m, near and far from the origin, lit
  // from their front side; sample points on each (float barycentrics) must all be lit.
  for (uint64_t seed = 0; seed < 60; ++seed) {
    auto rnd = [&](uint64_t dim) { return double(rng_float(rng_hash(0, seed, 77, dim))); };
    const double size = std::pow(10.0, -2.0 + 4.0 * rnd(0));
    const double offset = (seed % 3 == 0) ? 0.0 : std::pow(10.0, 1.0 + 3.0 * rnd(1));
    const dvec3 origin(offset, -0.5 * offset, 0.25 * offset);
    Scene s;
    s.materials.push_back(Material{});
    Mesh m;
    for (int v = 0; v < 3; ++v)
      m.positions.push_back(vec3(origin + size * dvec3(rnd(10 + 3 * v) - 0.5, rnd(11 + 3 * v) - 0.5,
                                                       rnd(12 + 3 * v) - 0.5)));
    m.indices = {0, 1, 2};
    compute_vertex_normals(m);
    vec3 n = glm::normalize(glm::cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0]));
    s.meshes.push_back(m);
    // At least ~1.3·size in front of the triangle's plane (the plane passes within 0.87·size of
    // the box centre `origin`).
    s.light.position = vec3(origin + dvec3(n) * (3.0 * size) +
                            size * dvec3(rnd(20) - 0.5, rnd(21) - 0.5, rnd(22) - 0.5));
    const EmbreeScene rt(s);
    std::vector<vec3> pts;
    for (int i = 0; i < 64; ++i) {
      float a = rng_float(rng_hash(uint64_t(i), seed, 78, 0));
      float b = rng_float(rng_hash(uint64_t(i), seed, 78, 1));
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      pts.push_back((1.0f - a - b) * m.positions[0] + a * m.positions[1] + b * m.positions[2]);
    }
    GBuffer g = gbuffer_of(pts, 8, n);
    for (size_t i = 0; i < pts.size(); ++i)
      if (glm::dot(n, s.light.position - pts[i]) <= 0.0f) g.covered[i] = 0;  // rare grazing case
    const ImageF mask = hard_visibility(rt, s, g);
    for (size_t i = 0; i < mask.data.size(); ++i)
      ASSERT_EQ(mask.data[i], 1.0f) << "seed " << seed << " size " << size << " offset " << offset
                                    << " point " << i;
  }
}

}  // namespace
}  // namespace shadowlab
