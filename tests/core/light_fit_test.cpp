// The light against its scene (core/light_fit.h) and the one rule for lists (core/repeats.h,
// core/spec.h same_spec), against values worked out by hand.
#include "core/light_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/repeats.h"
#include "core/spec.h"

namespace shadowlab {
namespace {

// A scene whose bounds are the box [lo, hi] (two triangles spanning its diagonal corners).
Scene box_scene(vec3 lo, vec3 hi) {
  Scene s;
  s.materials.resize(1);
  Mesh m;
  m.positions = {lo, hi, vec3(lo.x, hi.y, lo.z)};
  m.indices = {0, 1, 2};
  s.meshes.push_back(m);
  return s;
}

TEST(LightFit, CoveringFarReachesTheFarthestCorner) {
  Scene s = box_scene(vec3(0.0f), vec3(2.0f, 1.0f, 2.0f));
  s.light.position = vec3(10.0f, 0.0f, 0.0f);
  s.light.far = 5.0f;
  s.light.near = 0.05f;
  // Farthest corner (0, 1, 2): sqrt(100 + 1 + 4).
  const float reach = std::sqrt(105.0f);
  EXPECT_NEAR(covering_far(s), 1.02f * reach, 1e-5f);
  cover_scene_with_light_range(s);
  EXPECT_NEAR(s.light.far, 1.02f * reach, 1e-5f);
  EXPECT_FLOAT_EQ(s.light.near, 1e-3f * s.light.far);  // min(0.05, 1e-3 × 10.45)
  // A far that covers already is kept.
  s.light.far = 100.0f;
  cover_scene_with_light_range(s);
  EXPECT_EQ(s.light.far, 100.0f);
}

TEST(LightFit, FloatDepthMustResolveTheScene) {
  Scene s = box_scene(vec3(-1.0f), vec3(1.0f));  // diagonal 2·sqrt(3)
  s.camera.eye = vec3(0.0f, 0.0f, 5.0f);
  s.light.position = vec3(0.0f, 3.0f, 0.0f);
  s.light.far = 10.0f;
  EXPECT_EQ(light_fit_problem(s).kind, LightFitProblem::None);
  EXPECT_DOUBLE_EQ(light_depth_step(s.light), 10.0 * std::ldexp(1.0, -23));
  // The limit: step = diagonal / 1000, i.e. a range of 2·sqrt(3)/1000 · 2^23 ≈ 29,058 m.
  const double limit = 2.0 * std::sqrt(3.0) / kDepthStepsPerScene * std::ldexp(1.0, 23);
  s.light.position = vec3(0.0f, float(0.99 * limit), 0.0f);
  s.light.far = float(0.99 * limit);
  EXPECT_EQ(light_fit_problem(s).kind, LightFitProblem::None);
  s.light.position = vec3(0.0f, float(1.01 * limit), 0.0f);
  s.light.far = float(1.01 * limit);
  EXPECT_EQ(light_fit_problem(s).kind, LightFitProblem::Depth);
  // A light 1e20 m away: the covering far itself stays finite, and is refused.
  s.light.position = vec3(1e20f, 0.0f, 0.0f);
  cover_scene_with_light_range(s);
  EXPECT_TRUE(std::isfinite(s.light.far));
  EXPECT_EQ(light_fit_problem(s).kind, LightFitProblem::Depth);
}

TEST(LightFit, SphereMustNotHoldTheCameraOrTheScene) {
  Scene s = box_scene(vec3(-1.0f), vec3(1.0f));
  s.light.position = vec3(0.0f);
  s.camera.eye = vec3(0.0f, 0.0f, 4.0f);
  s.light.radius = 1.7f;  // the corners are sqrt(3) ≈ 1.732 away
  EXPECT_EQ(light_fit_problem(s).kind, LightFitProblem::None);
  s.light.radius = 1.75f;
  EXPECT_EQ(light_fit_problem(s).kind, LightFitProblem::Scene);
  s.light.radius = 4.0f;  // the eye is exactly on the sphere: inside counts
  EXPECT_EQ(light_fit_problem(s).kind, LightFitProblem::Camera);
  EXPECT_THROW(validate_scene(s, "test"), InputError);
}

TEST(LightFit, SceneSpanInTexels) {
  Scene s = box_scene(vec3(-1.0f), vec3(1.0f));  // bounding sphere radius sqrt(3)
  s.light.position = vec3(0.0f, 0.0f, 100.0f);
  const double expect = 2.0 * std::asin(std::sqrt(3.0) / 100.0) / (0.5 * M_PI) * 512.0;
  EXPECT_NEAR(scene_span_texels(s, 512), expect, 1e-9 * expect);  // ≈ 11.3
  s.light.position = vec3(0.5f, 0.0f, 0.0f);  // inside the sphere
  EXPECT_TRUE(std::isinf(scene_span_texels(s, 16)));
}

TEST(Repeats, ValuesAreComparedAsParsed) {
  EXPECT_NO_THROW(reject_repeats("--resolutions", std::vector<int>{64, 128}));
  try {
    reject_repeats("--resolutions", std::vector<int>{64, 128, 64}, {"64", "128", "064"});
    FAIL() << "64 and 064 are one value";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "--resolutions");
    EXPECT_NE(e.reason.find("'064' (the same as '64') given twice"), std::string::npos) << e.reason;
  }
  EXPECT_THROW(reject_repeats("--budget-ms", std::vector<double>{4.0, 4.0}), InputError);
  const auto spec = [](const char* t) { return parse_spec(t, "--techniques"); };
  EXPECT_TRUE(same_spec(spec("csm:pcf=3"), spec("csm:pcf=03")));
  EXPECT_TRUE(same_spec(spec("csm:bias=0.01,pcf=3"), spec("csm:pcf=3,bias=1e-2")));
  EXPECT_FALSE(same_spec(spec("csm:pcf=3"), spec("csm:pcf=5")));
  EXPECT_FALSE(same_spec(spec("csm"), spec("csm:pcf=1")));  // defaults are not filled in
  EXPECT_FALSE(same_spec(spec("csm:pcf=3"), spec("tsm:pcf=3")));
  EXPECT_TRUE(same_spec(spec("cmsm:variant=hausdorff"), spec("cmsm:variant=hausdorff")));
  EXPECT_FALSE(same_spec(spec("cmsm:variant=hausdorff"), spec("cmsm:variant=hamburger")));
}

}  // namespace
}  // namespace shadowlab
