// The slide projector in the techniques: the one-face projector layout, psm against the Embree
// hard reference, the frustum gate of run_technique, stored depth precision (depth=), and the
// shaded image (techniques/shading/projector_shading.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scenes/mesh_builders.h"
#include "core/slide.h"
#include "techniques/pipeline/light_map.h"
#include "techniques/pipeline/depth_quantize.h"
#include "techniques/pipeline/light_faces.h"
#include "techniques/shading/projector_shading.h"
#include "test_paths.h"
#include "test_scenes.h"

namespace shadowlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Slide coordinates of p per core/projector.h's header, computed independently in double:
// forward = normalize(direction), right = normalize(forward × up), up' = right × forward,
// s = ½ + ½·(d·right)/(z·tan_x), t = ½ − ½·(d·up')/(z·tan_y), z = d·forward; false for z <= 0.
bool hand_st(const Projector& p, const vec3& point, double& s, double& t) {
  const glm::dvec3 f = glm::normalize(glm::dvec3(p.direction));
  const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(p.up)));
  const glm::dvec3 u = glm::cross(r, f);
  const double tan_y = std::tan(double(p.fov_y_deg) * kPi / 360.0), tan_x = double(p.aspect) * tan_y;
  const glm::dvec3 d = glm::dvec3(point) - glm::dvec3(p.position);
  const double z = glm::dot(d, f);
  if (!(z > 0.0)) return false;
  s = 0.5 + 0.5 * glm::dot(d, r) / (z * tan_x);
  t = 0.5 - 0.5 * glm::dot(d, u) / (z * tan_y);
  return true;
}
// Inside the frustum by a margin (st in [m, 1 − m]); clearly outside: beyond it by m.
bool clearly_inside(const Projector& p, const vec3& point, double m) {
  double s, t;
  return hand_st(p, point, s, t) && s > m && s < 1 - m && t > m && t < 1 - m;
}
bool clearly_outside(const Projector& p, const vec3& point, double m) {
  double s, t;
  return !hand_st(p, point, s, t) || s < -m || s > 1 + m || t < -m || t > 1 + m;
}

// The projector of an unposed scene as lab/cli.cpp builds it: at the light, aimed at
// the camera target, up +y, fov 60°, aspect 1.
Projector cli_pose(const Scene& scene, const std::string& slide) {
  Projector p;
  p.position = scene.light.position;
  p.direction = scene.camera.target - scene.light.position;
  p.up = vec3(0.0f, 1.0f, 0.0f);
  p.fov_y_deg = 60.0f;
  p.aspect = 1.0f;
  p.slide = make_slide(slide, "--slide");
  return p;
}

// Frustum corner directions forward ± tan_x·right ± tan_y·up have plane coordinates
// (±tan_x, ±tan_y), the owned region's corners: texel x = guard (left) or guard + W (right),
// y = guard (top) or guard + N (bottom), W = round(N·aspect).
TEST(ProjectorLayout, FrustumCornersMapToOwnedRegionCorners) {
  Projector p;
  p.position = vec3(0.3f, 1.7f, -2.0f);
  p.direction = vec3(0.4f, -0.3f, 1.0f);
  p.up = vec3(0.1f, 1.0f, 0.0f);
  p.fov_y_deg = 45.0f;
  p.aspect = 1.37f;
  const int N = 64, guard = 3, W = 88;  // round(64 × 1.37) = round(87.68) = 88
  const FaceLayout L = projector_layout(p, N, guard);
  ASSERT_EQ(L.faces.size(), 1u);
  const LightFace& f = L.faces[0];
  ASSERT_EQ(f.width, W + 2 * guard);
  ASSERT_EQ(f.height, N + 2 * guard);
  const glm::dvec3 fw = glm::normalize(glm::dvec3(p.direction));
  const glm::dvec3 rt = glm::normalize(glm::cross(fw, glm::dvec3(p.up)));
  const glm::dvec3 up = glm::cross(rt, fw);
  const double ty = std::tan(45.0 * kPi / 360.0), tx = 1.37 * ty;
  for (int sx : {-1, 1})
    for (int sy : {-1, 1}) {
      const vec3 dir(glm::normalize(fw + double(sx) * tx * rt + double(sy) * ty * up));
      const vec2 c = face_texel_coords(f, dir);
      EXPECT_NEAR(c.x, sx < 0 ? guard : guard + W, 1e-3) << sx << "," << sy;
      EXPECT_NEAR(c.y, sy > 0 ? guard : guard + N, 1e-3) << sx << "," << sy;
    }
  // The axis lands on the centre of the image.
  const vec2 centre = face_texel_coords(f, vec3(fw));
  EXPECT_NEAR(centre.x, 0.5 * f.width, 1e-3);
  EXPECT_NEAR(centre.y, 0.5 * f.height, 1e-3);
}

struct Agreement {
  size_t covered = 0, inside = 0, agree_inside = 0, lit = 0, cast_shadow = 0, outside = 0,
         outside_nonzero = 0;
};
// Compares psm with the hard Embree reference on covered pixels clearly inside the frustum and
// counts (from the reference) the lit ones and the cast-shadowed ones (facing the light, yet
// occluded); pixels clearly outside it must be 0 in both masks.
Agreement compare_with_reference(const Scene& scene, const GBuffer& g, const ShadowResult& psm,
                                 const ShadowResult& ref) {
  Agreement a;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i]) continue;
    ++a.covered;
    if (clearly_outside(scene.projector, g.position[i], 1e-4)) {
      ++a.outside;
      a.outside_nonzero += psm.mask.data[i] != 0.0f || ref.mask.data[i] != 0.0f;
    } else if (clearly_inside(scene.projector, g.position[i], 1e-4)) {
      ++a.inside;
      a.agree_inside += (psm.mask.data[i] > 0.5f) == (ref.mask.data[i] > 0.5f);
      if (ref.mask.data[i] > 0.5f) ++a.lit;
      else if (faces_light(g, i, scene.light.position)) ++a.cast_shadow;
    }
  }
  return a;
}

void expect_agreement(const Scene& scene, const std::string& what) {
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult psm = test::run("psm:res=1024,pcf=1", scene, g);
  const ShadowResult ref = test::run("rt:hard=1", scene, g);
  const Agreement a = compare_with_reference(scene, g, psm, ref);
  ASSERT_GT(a.covered, g.pixel_count() / 2) << what;
  // Judged on the pixels inside the frustum (outside, both are 0 by the gate, checked below, and
  // would only dilute the rate). Threshold 98 %: a 1024-texel map over the frustum gives one to
  // a few texels per pixel, so only pixels along shadow silhouettes (about one pixel wide) and
  // bias-limited contact pixels can differ.
  EXPECT_GE(double(a.agree_inside) / double(a.inside), 0.98)
      << what << ": " << a.inside - a.agree_inside << " of " << a.inside << " pixels inside differ";
  // The gate: outside the frustum both masks are exactly 0.
  EXPECT_EQ(a.outside_nonzero, 0u) << what;
  // Not vacuous: pixels outside the frustum, and inside it real lit and cast-shadow areas.
  // (The scenes' poses light the bunny / the room corner broadly: cast shadows are 3.7 % /
  // 4.7 % of the pixels inside, hence 2 % and an absolute floor rather than 5 %.)
  EXPECT_GT(a.outside, a.covered / 20) << what;
  EXPECT_GT(a.lit, a.inside / 2) << what;
  EXPECT_GT(a.cast_shadow, a.inside / 50) << what;
  EXPECT_GT(a.cast_shadow, 150u) << what;
}

TEST(ProjectorShadows, PsmMatchesHardRayTracingOnBunny) {
  Scene scene = make_builtin_scene("bunny");
  apply_camera_size(scene, 256, 192);
  Projector p = scene.projector;  // the scene's own pose
  ASSERT_TRUE(p.posed);
  p.slide = make_slide("spot", "--slide");
  set_projector(scene, p, "test");
  EXPECT_EQ(scene.light.radius, 0.0f);
  expect_agreement(scene, "bunny");
}

TEST(ProjectorShadows, PsmMatchesHardRayTracingOnDefaultScene) {
  Scene scene = test::small_scene("default", 256, 192);
  set_projector(scene, cli_pose(scene, "spot"), "test");
  expect_agreement(scene, "default");
}

TEST(ProjectorShadows, PsmWithoutProjectorIsInputError) {
  const Scene scene = test::small_scene("default", 32, 24);
  const GBuffer g = render_gbuffer(scene);
  EXPECT_THROW(test::run("psm:res=64", scene, g), InputError);
}

// The gate applies to every technique: csm (which knows nothing of projectors) leaves 0 on
// every covered pixel outside the frustum, and still lights pixels inside it.
TEST(ProjectorShadows, CubeMapIsGatedByTheFrustum) {
  Scene scene = test::small_scene("default", 160, 120);
  Projector p = cli_pose(scene, "spot");
  p.fov_y_deg = 40.0f;  // narrower than the camera's view: many pixels outside
  set_projector(scene, p, "test");
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult r = test::run("csm:res=256", scene, g);
  size_t outside = 0, inside_lit = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i) {
    if (!g.covered[i]) {
      EXPECT_EQ(r.mask.data[i], 1.0f) << "uncovered pixel " << i;  // mask convention
      continue;
    }
    if (clearly_outside(scene.projector, g.position[i], 1e-4)) {
      ++outside;
      EXPECT_EQ(r.mask.data[i], 0.0f) << "pixel " << i;
      EXPECT_EQ(r.texels.data[i], kNoTexel) << "pixel " << i;
    } else if (clearly_inside(scene.projector, g.position[i], 1e-4)) {
      inside_lit += r.mask.data[i] > 0.5f;
    }
  }
  EXPECT_GT(outside, g.pixel_count() / 10);
  EXPECT_GT(inside_lit, g.pixel_count() / 50);
  // Not vacuous: the ungated cube map (a point light lights all around) lights many of those
  // outside pixels; the zeros come from the gate.
  RunOptions opt;
  const ShadowResult ungated =
      run_light_map(parse_map_params(parse_technique_spec("csm:res=256", "--technique"),
                                     FaceLayoutKind::Cube, MapFilter::Depth, "--technique"),
                    scene, g, opt);
  size_t outside_lit = 0;
  for (size_t i = 0; i < g.pixel_count(); ++i)
    outside_lit += g.covered[i] && clearly_outside(scene.projector, g.position[i], 1e-4) &&
                   ungated.mask.data[i] > 0.5f;
  EXPECT_GT(outside_lit, g.pixel_count() / 20);  // 647 of 19,200 when written
}

// Quantization steps: linear n-bit codes k/(2ⁿ − 1) are at most half a step, 0.5/(2ⁿ − 1), from
// d; the cubic code c' = round(255·∛d)/255 is within δ = 0.5/255 of c = ∛d, so
// |c'³ − c³| ≤ 3c²δ + 3cδ² + δ³ (the first term is half the step 3·d^(2/3)/255).
TEST(DepthQuantize, ErrorsWithinHalfAStep) {
  const double eps = 2e-7;  // float rounding of the decoded value
  for (int i = 0; i <= 1000; ++i) {
    const float d = float(i) / 1000.0f * 0.999f + (i % 7) * 1e-6f;
    const double dd = d;
    const float q16 = quantize_depth(d, DepthFormat::U16), q8 = quantize_depth(d, DepthFormat::U8);
    EXPECT_LE(std::fabs(q16 - dd), 0.5 / 65535.0 + eps) << d;
    EXPECT_LE(std::fabs(q8 - dd), 0.5 / 255.0 + eps) << d;
    // The decoded values are codes.
    EXPECT_NEAR(double(q8) * 255.0, std::round(double(q8) * 255.0), 1e-4) << d;
    EXPECT_NEAR(double(q16) * 65535.0, std::round(double(q16) * 65535.0), 1e-2) << d;
    const double c = std::cbrt(dd), delta = 0.5 / 255.0;
    const float qc = quantize_depth(d, DepthFormat::U8Cubic);
    EXPECT_LE(std::fabs(qc - dd), 3 * c * c * delta + 3 * c * delta * delta + delta * delta * delta + eps) << d;
    EXPECT_NEAR(std::cbrt(double(qc)) * 255.0, std::round(std::cbrt(double(qc)) * 255.0), 1e-3) << d;
    EXPECT_EQ(quantize_depth(d, DepthFormat::F32), d);
  }
  // Near the light the cubic ramp is much finer than linear 8-bit: at d = 0.01, half-step bound
  // 3·0.01^(2/3)/255/2 = 2.7e-4 vs 2.0e-3.
  EXPECT_LE(std::fabs(quantize_depth(0.01f, DepthFormat::U8Cubic) - 0.01), 2.8e-4);
  const float inf = std::numeric_limits<float>::infinity();
  for (DepthFormat f : {DepthFormat::F32, DepthFormat::U16, DepthFormat::U8, DepthFormat::U8Cubic}) {
    EXPECT_EQ(quantize_depth(inf, f), inf);
    if (f != DepthFormat::F32) {
      EXPECT_EQ(quantize_depth(1.7f, f), 1.0f);  // above 1 clamps to the top code, which decodes to 1
      EXPECT_EQ(quantize_depth(0.0f, f), 0.0f);
      EXPECT_EQ(quantize_depth(1.0f, f), 1.0f);
    }
  }
  EXPECT_EQ(quantize_depth(1.7f, DepthFormat::F32), 1.7f);
  std::vector<float> v = {0.1f, 0.5f, inf, 2.0f};
  quantize_depths(v.data(), v.size(), DepthFormat::U8);
  EXPECT_EQ(v[0], quantize_depth(0.1f, DepthFormat::U8));
  EXPECT_EQ(v[2], inf);
  EXPECT_EQ(v[3], 1.0f);
}

size_t differing(const ImageF& a, const ImageF& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.data.size(); ++i) n += (a.data[i] > 0.5f) != (b.data[i] > 0.5f);
  return n;
}

// The default scene's light far is 20 m: a 16-bit step is 20/65535 = 0.3 mm ≪ the 1 cm bias,
// so depth=16 matches f32 almost everywhere; an 8-bit step is 20/255 = 7.8 cm ≫ the bias, so
// stored depths rounded down by up to 3.9 cm self-shadow lit surfaces (acne).
TEST(DepthQuantize, SixteenBitsMatchFloatEightBitsShowAcne) {
  const Scene scene = test::small_scene("default", 160, 120);
  ASSERT_EQ(scene.light.far, 20.0f);
  const GBuffer g = render_gbuffer(scene);
  const ShadowResult f32 = test::run("csm:res=256,depth=f32", scene, g);
  const ShadowResult d16 = test::run("csm:res=256,depth=16", scene, g);
  const ShadowResult d8 = test::run("csm:res=256,depth=8", scene, g);
  const size_t n = g.pixel_count(), diff16 = differing(d16.mask, f32.mask), diff8 = differing(d8.mask, f32.mask);
  EXPECT_LE(double(diff16) / double(n), 0.005) << diff16 << " of " << n;
  EXPECT_GT(diff8, n / 20) << "8-bit acne: " << diff8 << " of " << n;  // 1,621 of 19,200 when written
  EXPECT_GT(diff8, 10 * diff16 + 10) << diff8 << " vs " << diff16;
  // Acne darkens: the 8-bit map loses lit pixels rather than gaining them.
  size_t lost = 0;
  for (size_t i = 0; i < n; ++i) lost += f32.mask.data[i] > 0.5f && d8.mask.data[i] <= 0.5f;
  EXPECT_GT(lost, diff8 / 2);
}

TEST(DepthQuantize, UnknownDepthIsInputErrorNamingTheFlag) {
  for (const char* spec : {"csm:depth=12", "tsm:depth=12", "psm:depth=12", "csm:depth=F32"}) {
    try {
      validate_technique(parse_technique_spec(spec, "--technique"), "--technique");
      ADD_FAILURE() << spec << ": no InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where, "--technique") << spec;
      EXPECT_NE(e.reason.find("depth"), std::string::npos) << spec << ": " << e.what();
    }
  }
}

// One floor quad (y = 0, facing +y, 3 × 3 m) under a projector 1 m above the origin looking
// straight down (fov 60°, spot); the camera looks straight down from 3 m with an odd image
// size, so its centre pixel sees the origin. With visibility 1:
//   below the projector: N·L = 1, spot centre = 1 → ambient·albedo + albedo;
//   well inside the spot's flat core (r < 0.5): albedo·(ambient + 1/|p − L|) (N·L = 1/|p − L|);
//   outside the frustum (|x| or |z| > tan 30° = 0.577 m): ambient·albedo; uncovered: 0.
TEST(ProjectorShading, FloorUnderProjectorMatchesAnalyticShading) {
  Scene s;
  s.name = "floor";
  const vec3 albedo(0.5f, 0.25f, 0.8f);
  add_grid_quad(new_mesh(s, "floor", albedo), vec3(-1.5f, 0.0f, 1.5f), vec3(3.0f, 0.0f, 0.0f),
                vec3(0.0f, 0.0f, -3.0f), 4, 4);
  s.camera.eye = vec3(0.0f, 3.0f, 0.0f);
  s.camera.target = vec3(0.0f);
  s.camera.up = vec3(0.0f, 0.0f, -1.0f);
  s.camera.fov_y_deg = 60.0f;
  s.camera.near = 0.05f;
  s.camera.far = 10.0f;
  s.camera.width = 161;
  s.camera.height = 121;
  s.light.position = vec3(0.0f, 1.0f, 0.0f);
  Projector p;
  p.position = vec3(0.0f, 1.0f, 0.0f);
  p.direction = vec3(0.0f, -1.0f, 0.0f);
  p.up = vec3(0.0f, 0.0f, -1.0f);
  p.fov_y_deg = 60.0f;
  p.aspect = 1.0f;
  p.slide = make_slide("spot:res=64", "--slide");
  set_projector(s, p, "test");
  validate_scene(s, "test");
  const GBuffer g = render_gbuffer(s);
  const ImageF ones(g.width, g.height, 1, 1.0f);
  ProjectorShading sh;
  sh.ambient = 0.2f;
  const ImageF img = shade_projector(s, g, ones, sh);
  ASSERT_EQ(img.width, 161);
  ASSERT_EQ(img.height, 121);
  ASSERT_EQ(img.channels, 3);

  const size_t centre = size_t(60) * 161 + 80;
  ASSERT_TRUE(g.covered[centre]);
  ASSERT_LT(glm::length(g.position[centre]), 1e-4f) << "the centre pixel must see the origin";
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(img.at(80, 60, c), 0.2f * albedo[c] + albedo[c], 1e-5) << "channel " << c;

  const double tan30 = std::tan(kPi / 6.0);
  size_t core = 0, outside = 0, uncovered = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = size_t(y) * size_t(g.width) + size_t(x);
      if (!g.covered[i]) {
        ++uncovered;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(img.at(x, y, c), 0.0f) << x << "," << y;
        continue;
      }
      const vec3 q = g.position[i];
      const double rho = std::hypot(double(q.x), double(q.z));  // 1 m below the projector
      if (std::fabs(q.x) > tan30 + 1e-3 || std::fabs(q.z) > tan30 + 1e-3) {
        ++outside;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y, c), 0.2f * albedo[c], 1e-6) << x << "," << y;
      } else if (rho < 0.5 * tan30) {
        // r = ρ/tan 30° < 0.5: inside the flat core r < 0.6 by more than the bilinear reach of
        // the 64² bake (√2 texels = 0.044 in r), so the slide reads exactly 1.
        ++core;
        const double dist = std::sqrt(rho * rho + 1.0);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(img.at(x, y, c), albedo[c] * (0.2 + 1.0 / dist), 1e-5) << x << "," << y;
      }
    }
  EXPECT_GT(core, 200u);  // π·(0.29 m / 0.0286 m per pixel)² ≈ 320
  EXPECT_GT(outside, 500u);
  EXPECT_GT(uncovered, 500u);

  // Visibility scales the projector term only: 0 → ambient, 0.5 → ambient + half.
  ImageF half(g.width, g.height, 1, 0.5f);
  half.data[centre + 1] = 0.0f;
  const ImageF img2 = shade_projector(s, g, half, sh);
  EXPECT_NEAR(img2.at(80, 60, 0), albedo[0] * 0.7f, 1e-5);
  EXPECT_NEAR(img2.at(81, 60, 0), albedo[0] * 0.2f, 1e-6);
}

}  // namespace
}  // namespace shadowlab
