// EmbreeScene construction, primary visibility and alpha-tested geometry.
#include "raytrace/embree_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <type_traits>

#include "core/rng.h"
#include "core/texture.h"
#include "raytrace/visibility.h"
#include "scenes/mesh_builders.h"

namespace shadowlab {
namespace {

// The quad a, b, c, d (counter-clockwise from its front) as one mesh (scenes/mesh_builders.h).
int add_quad(Scene& scene, vec3 a, vec3 b, vec3 c, vec3 d, int material = 0,
             std::vector<vec2> uvs = {}) {
  return add_quad_mesh(scene, a, b, c, d, material, std::move(uvs));
}

// Horizontal quad at height y over [x0, x1] × [z0, z1], front face up, uv = ((x − x0)/(x1 − x0),
// (z − z0)/(z1 − z0)), so u grows with x and v with z.
int add_horizontal_uv(Scene& scene, float y, float x0, float x1, float z0, float z1, int material) {
  return add_quad(scene, vec3(x0, y, z1), vec3(x1, y, z1), vec3(x1, y, z0), vec3(x0, y, z0),
                  material, {vec2(0, 1), vec2(1, 1), vec2(1, 0), vec2(0, 0)});
}

GBuffer points_gbuffer(const std::vector<vec3>& points, vec3 normal) {
  GBuffer g;
  g.resize(int(points.size()), 1);
  for (size_t i = 0; i < points.size(); ++i) {
    g.position[i] = points[i];
    g.geo_normal[i] = normal;
    g.normal[i] = normal;
    g.covered[i] = 1;
  }
  return g;
}

Camera camera_at_origin(int w, int h) {
  Camera c;
  c.eye = vec3(0.0f);
  c.target = vec3(0.0f, 0.0f, -1.0f);
  c.up = vec3(0.0f, 1.0f, 0.0f);
  c.fov_y_deg = 60.0f;
  c.width = w;
  c.height = h;
  return c;
}

static_assert(!std::is_copy_constructible_v<EmbreeScene>);
static_assert(std::is_nothrow_move_constructible_v<EmbreeScene>);

TEST(EmbreeScene, EmptySceneIsAllLit) {
  Scene s;
  s.light.position = vec3(0, 3, 0);
  s.light.radius = 0.5f;
  const EmbreeScene rt(s);
  EXPECT_EQ(rt.scene_scale(), 0.0f);
  EXPECT_EQ(rt.mesh_count(), 0u);
  const GBuffer g = points_gbuffer({vec3(0, 0, 0), vec3(1, 0, 1), vec3(-2, 0, 0)}, vec3(0, 1, 0));
  for (float v : hard_visibility(rt, s, g).data) EXPECT_EQ(v, 1.0f);
  for (float v : soft_visibility(rt, s, g, 9, 1).data) EXPECT_EQ(v, 1.0f);
  const PrimaryHits hits = primary_visibility(rt, camera_at_origin(8, 6));
  for (uint32_t id : hits.mesh_id) EXPECT_EQ(id, kNoPrimitive);
  for (float d : hits.depth) EXPECT_TRUE(std::isinf(d));
}

TEST(EmbreeScene, SceneScaleIsTheBoundsDiagonal) {
  Scene s;
  s.materials.push_back(Material{});
  add_quad(s, vec3(0, 0, 0), vec3(3, 0, 0), vec3(3, 4, 0), vec3(0, 4, 12));
  const EmbreeScene rt(s);
  EXPECT_FLOAT_EQ(rt.scene_scale(), 13.0f);  // √(3² + 4² + 12²)
}

TEST(EmbreeScene, RejectsBadInputAndIsMovable) {
  Scene bad;
  bad.materials.push_back(Material{});
  add_quad(bad, vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, std::numeric_limits<float>::quiet_NaN(), 0),
           vec3(0, 1, 0));
  EXPECT_THROW(EmbreeScene{bad}, InputError);

  Scene s;
  s.materials.push_back(Material{});
  add_quad(s, vec3(-1, -1, -2), vec3(1, -1, -2), vec3(1, 1, -2), vec3(-1, 1, -2));
  EmbreeScene a(s);
  EmbreeScene b(std::move(a));
  EmbreeScene c(Scene{});
  c = std::move(b);
  const PrimaryHits hits = primary_visibility(c, camera_at_origin(4, 4));
  EXPECT_EQ(hits.mesh_id[5], 0u);  // the quad fills the centre of the view
}

TEST(PrimaryVisibility, FrontalQuadHasConstantDepth) {
  // Plane z = −5 facing the camera at the origin: view-space depth 5 at every pixel.
  Scene s;
  s.materials.push_back(Material{});
  add_quad(s, vec3(-10, -10, -5), vec3(10, -10, -5), vec3(10, 10, -5), vec3(-10, 10, -5));
  const EmbreeScene rt(s);
  const PrimaryHits hits = primary_visibility(rt, camera_at_origin(32, 24));
  ASSERT_EQ(hits.width, 32);
  ASSERT_EQ(hits.height, 24);
  for (size_t i = 0; i < hits.depth.size(); ++i) {
    EXPECT_EQ(hits.mesh_id[i], 0u);
    EXPECT_LT(hits.prim_id[i], 2u);
    EXPECT_NEAR(hits.depth[i], 5.0f, 5e-5f) << "pixel " << i;
  }
}

TEST(PrimaryVisibility, TiltedPlaneDepthFollowsPixelCentres) {
  // Plane y + z = −5. The ray through pixel (x, y) has view direction (a, b, −1) with
  // b = ndc_y·tan 30°, ndc_y = 1 − 2(y + 0.5)/H (image y down), so b·t − t = −5: depth 5/(1 − b).
  Scene s;
  s.materials.push_back(Material{});
  add_quad(s, vec3(-50, 50, -55), vec3(-50, -50, 45), vec3(50, -50, 45), vec3(50, 50, -55));
  const EmbreeScene rt(s);
  const int w = 20, h = 15;
  const PrimaryHits hits = primary_visibility(rt, camera_at_origin(w, h));
  const double tan30 = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double b = (1.0 - 2.0 * (y + 0.5) / h) * tan30;
      const size_t i = size_t(y) * w + x;
      ASSERT_EQ(hits.mesh_id[i], 0u) << x << "," << y;
      EXPECT_NEAR(hits.depth[i], 5.0 / (1.0 - b), 1e-4) << x << "," << y;
    }
}

TEST(PrimaryVisibility, ImageOrientationAndMeshIds) {
  // Mesh 0 is empty (its geomID stays unused); mesh 1 covers view x > 0, y > 0 at z = −5
  // (top-right quarter of the image); mesh 2 covers x < 0, y < 0 at z = −3 (bottom-left).
  Scene s;
  s.materials.push_back(Material{});
  s.meshes.push_back(Mesh{});
  add_quad(s, vec3(0, 0, -5), vec3(10, 0, -5), vec3(10, 10, -5), vec3(0, 10, -5));
  add_quad(s, vec3(-10, -10, -3), vec3(0, -10, -3), vec3(0, 0, -3), vec3(-10, 0, -3));
  const EmbreeScene rt(s);
  const int w = 16, h = 12;
  const PrimaryHits hits = primary_visibility(rt, camera_at_origin(w, h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const bool right = x >= w / 2, top = y < h / 2;
      if (right && top) {
        EXPECT_EQ(hits.mesh_id[i], 1u) << x << "," << y;
        EXPECT_NEAR(hits.depth[i], 5.0f, 5e-5f);
      } else if (!right && !top) {
        EXPECT_EQ(hits.mesh_id[i], 2u) << x << "," << y;
        EXPECT_NEAR(hits.depth[i], 3.0f, 5e-5f);
      } else {
        EXPECT_EQ(hits.mesh_id[i], kNoPrimitive) << x << "," << y;
        EXPECT_EQ(hits.prim_id[i], kNoPrimitive);
        EXPECT_TRUE(std::isinf(hits.depth[i]));
      }
    }
}

TEST(PrimaryVisibility, GeometryOutsideNearFarIsClipped) {
  Scene s;
  s.materials.push_back(Material{});
  add_quad(s, vec3(-1, -1, -0.01f), vec3(1, -1, -0.01f), vec3(1, 1, -0.01f), vec3(-1, 1, -0.01f));
  add_quad(s, vec3(-500, -500, -200), vec3(500, -500, -200), vec3(500, 500, -200),
           vec3(-500, 500, -200));
  const EmbreeScene rt(s);
  Camera c = camera_at_origin(4, 4);
  c.near = 0.05f;
  c.far = 100.0f;
  for (uint32_t id : primary_visibility(rt, c).mesh_id) EXPECT_EQ(id, kNoPrimitive);
  c.far = 300.0f;
  for (uint32_t id : primary_visibility(rt, c).mesh_id) EXPECT_EQ(id, 1u);
}

// Occluder y = 2 over [−5, 5]² with u = (x + 5)/10; a 4 × 1 alpha texture
// [0, 0.49, 0.5, 1] with cutoff 0.5: hits with x < 0 (u < 0.5) are discarded, alpha = cutoff kept.
Scene alpha_scene() {
  Scene s;
  s.materials.push_back(Material{});
  Material leaf;
  leaf.name = "leaf";
  leaf.alpha_texture = 0;
  leaf.alpha_cutoff = 0.5f;
  s.materials.push_back(leaf);
  ImageF tex(4, 1, 4, 1.0f);
  const float alphas[4] = {0.0f, 0.49f, 0.5f, 1.0f};
  for (int x = 0; x < 4; ++x) tex.at(x, 0, 3) = alphas[x];
  s.textures.push_back(tex);
  add_quad(s, vec3(-10, 0, 10), vec3(10, 0, 10), vec3(10, 0, -10), vec3(-10, 0, -10));  // floor
  add_horizontal_uv(s, 2.0f, -5.0f, 5.0f, -5.0f, 5.0f, 1);
  s.light.position = vec3(0, 4, 0);
  return s;
}

TEST(AlphaFilter, TransparentHalfLetsShadowRaysThrough) {
  const Scene s = alpha_scene();
  const EmbreeScene rt(s);
  EXPECT_EQ(rt.alpha_mesh_count(), 1u);
  // Floor points at x = −7.5, −2.5, 2.5, 7.5: the rays to (0, 4, 0) cross y = 2 at half those x,
  // i.e. in texels 0, 1, 2, 3 (alphas 0, 0.49, 0.5, 1).
  const GBuffer g = points_gbuffer({vec3(-7.5f, 0, 1), vec3(-2.5f, 0, -1), vec3(2.5f, 0, 1),
                                    vec3(7.5f, 0, -1)},
                                   vec3(0, 1, 0));
  const ImageF m = hard_visibility(rt, s, g);
  EXPECT_EQ(m.data[0], 1.0f);
  EXPECT_EQ(m.data[1], 1.0f);
  EXPECT_EQ(m.data[2], 0.0f);
  EXPECT_EQ(m.data[3], 0.0f);
  // The same quad with an opaque material blocks all four.
  Scene opaque = s;
  opaque.meshes[1].material = 0;
  const EmbreeScene rt_opaque(opaque);
  EXPECT_EQ(rt_opaque.alpha_mesh_count(), 0u);
  for (float v : hard_visibility(rt_opaque, opaque, g).data) EXPECT_EQ(v, 0.0f);
}

TEST(AlphaFilter, VIsFlippedInTheFilter) {
  // A 1 × 2 texture: top row opaque, bottom row transparent. v = (z + 5)/10, so v < 0.5
  // (z < 0) reads the bottom row: rays crossing the occluder at z < 0 pass.
  Scene s = alpha_scene();
  ImageF tex(1, 2, 4, 1.0f);
  tex.at(0, 0, 3) = 1.0f;
  tex.at(0, 1, 3) = 0.0f;
  s.textures[0] = tex;
  const EmbreeScene rt(s);
  const GBuffer g = points_gbuffer({vec3(1, 0, -3), vec3(-1, 0, 3)}, vec3(0, 1, 0));
  const ImageF m = hard_visibility(rt, s, g);
  EXPECT_EQ(m.data[0], 1.0f);  // crosses at z = −1.5 → bottom row → transparent
  EXPECT_EQ(m.data[1], 0.0f);  // crosses at z = +1.5 → top row → opaque
}

TEST(AlphaFilter, MatchesCoreLookupAtTheCrossingPoint) {
  // 8 × 8 random binary alpha on the occluder; 400 random floor points. The ray from (x, 0, z)
  // to the light (0, 4, 0) crosses y = 2 at (x/2, z/2), i.e. uv = ((x/2 + 5)/10, (z/2 + 5)/10):
  // the pixel is lit iff core's lookup there fails the alpha test. Points whose crossing lies
  // within 1e-2 texel (12.5 mm) of a texel edge are skipped: the ray origin is lifted by the
  // self-intersection offset (1e-4 × the 28 m scene diagonal ≈ 3 mm), which moves the crossing
  // by up to ~3 mm.
  Scene s = alpha_scene();
  ImageF tex(8, 8, 4, 1.0f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      tex.at(x, y, 3) = (rng_hash(uint64_t(y * 8 + x), 0, 5) >> 63) ? 1.0f : 0.0f;
  s.textures[0] = tex;
  const EmbreeScene rt(s);
  std::vector<vec3> pts;
  std::vector<float> expected;
  for (uint64_t i = 0; pts.size() < 400; ++i) {
    const float x = -9.0f + 18.0f * rng_float(rng_hash(i, 1, 5));
    const float z = -9.0f + 18.0f * rng_float(rng_hash(i, 2, 5));
    const vec2 uv((0.5f * x + 5.0f) / 10.0f, (0.5f * z + 5.0f) / 10.0f);
    const float fu = uv.x * 8.0f - std::floor(uv.x * 8.0f), fv = uv.y * 8.0f - std::floor(uv.y * 8.0f);
    if (std::min(fu, 1.0f - fu) < 1e-2f || std::min(fv, 1.0f - fv) < 1e-2f) continue;
    pts.push_back(vec3(x, 0.0f, z));
    expected.push_back(alpha_test_passes(sample_alpha(tex, uv), 0.5f) ? 0.0f : 1.0f);
  }
  const ImageF m = hard_visibility(rt, s, points_gbuffer(pts, vec3(0, 1, 0)));
  int lit = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(m.data[i], expected[i]) << "point " << pts[i].x << ", " << pts[i].z;
    lit += expected[i] == 1.0f;
  }
  EXPECT_GT(lit, 100);
  EXPECT_LT(lit, 300);
}

TEST(AlphaFilter, NonRgbaAlphaTextureIsRejected) {
  Scene s = alpha_scene();
  s.textures[0] = ImageF(4, 1, 1, 1.0f);
  EXPECT_THROW(EmbreeScene{s}, InputError);
  s.textures[0] = ImageF();
  EXPECT_THROW(EmbreeScene{s}, InputError);
}

TEST(AlphaFilter, PrimaryRaysSeeThroughTransparentTexels) {
  // Camera 10 m above looking down (up = −z, so image right = +x): pixels over x < 0 see the
  // floor (depth 10), pixels over x > 0 the occluder (depth 8).
  const Scene s = alpha_scene();
  const EmbreeScene rt(s);
  Camera c;
  c.eye = vec3(0, 10, 0);
  c.target = vec3(0, 0, 0);
  c.up = vec3(0, 0, -1);
  c.fov_y_deg = 20.0f;  // footprint ±1.76 m on the occluder: inside [−5, 5]
  c.width = 8;
  c.height = 8;
  const PrimaryHits hits = primary_visibility(rt, c);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const size_t i = size_t(y) * 8 + x;
      if (x < 4) {
        EXPECT_EQ(hits.mesh_id[i], 0u) << x << "," << y;
        EXPECT_NEAR(hits.depth[i], 10.0f, 1e-4f);
      } else {
        EXPECT_EQ(hits.mesh_id[i], 1u) << x << "," << y;
        EXPECT_NEAR(hits.depth[i], 8.0f, 1e-4f);
      }
    }
}

}  // namespace
}  // namespace shadowlab
