// The data set's random choices (lab/nsm_dataset.h) against their stated bounds: the perturbed
// copies' light offsets within the ball and reaching its edge, the camera's within 0.5 px at
// the target's depth with eye and target moved together, crops inside the frame, splits.
#include <gtest/gtest.h>

#include <cmath>

#include "lab/nsm_dataset.h"
#include "scenes/scene_registry.h"

namespace shadowlab {
// A named namespace: the unity build compiles several test files in one translation unit.
namespace nsm_dataset_test {

TEST(NsmDataset, PerturbationsStayWithinTheirBounds) {
  NsmDatasetParams p;
  const Scene base = make_builtin_scene("default");
  double max_light = 0.0, max_cam = 0.0;
  for (int frame = 0; frame < 40; ++frame) {
    const Scene s0 = nsm_frame_scene(base, p, frame);
    const long double lt = glm::length(s0.light.position - s0.camera.target);
    const long double ball = std::max(2.0L * lt / p.base_res, 0.1L * 0.3L);
    const long double pixel = 2.0L * std::tan(s0.camera.fov_y_deg * 3.14159265358979323846L / 360.0L) *
                              glm::length(s0.camera.target - s0.camera.eye) / p.height;
    for (int c = 1; c <= 3; ++c) {
      const Scene s = nsm_perturbed_scene(s0, p, frame, c);
      const long double dl = glm::length(s.light.position - s0.light.position);
      EXPECT_LE(dl, ball * (1 + 1e-5L)) << frame << " " << c;
      max_light = std::max(max_light, double(dl / ball));
      const vec3 de = s.camera.eye - s0.camera.eye, dt = s.camera.target - s0.camera.target;
      EXPECT_NEAR(glm::length(de - dt), 0.0, 1e-5);
      // In the image plane: perpendicular to the view direction.
      EXPECT_NEAR(glm::dot(de, glm::normalize(s0.camera.target - s0.camera.eye)), 0.0, 1e-5);
      const long double dc = glm::length(de);
      EXPECT_LE(dc, 0.5L * pixel * (1 + 1e-4L) + 1e-6L) << frame << " " << c;
      max_cam = std::max(max_cam, double(dc / pixel));
    }
  }
  // 120 uniform draws in the ball reach past 0.8 of its radius (P(miss) = 0.512^120), and in
  // the disk past 0.4 px (P(miss) = 0.64^120).
  EXPECT_GT(max_light, 0.8);
  EXPECT_GT(max_cam, 0.4);
}

TEST(NsmDataset, CropsLieInsideTheFrame) {
  NsmDatasetParams p;
  p.width = 100;
  p.height = 60;
  p.crop_w = 40;
  p.crop_h = 60;
  int lo = 100, hi = 0;
  for (int frame = 0; frame < 200; ++frame) {
    const auto c = nsm_frame_crop(p, frame);
    EXPECT_GE(c[0], 0);
    EXPECT_LE(c[0] + c[2], p.width);
    EXPECT_EQ(c[1], 0);  // the window is as tall as the frame
    lo = std::min(lo, c[0]);
    hi = std::max(hi, c[0]);
  }
  EXPECT_LE(lo, 2);
  EXPECT_GE(hi, 58);
}

TEST(NsmDataset, SplitFractionsAndHeldOutScenes) {
  NsmDatasetParams p;
  p.val.fraction = 0.2;
  p.test.fraction = 0.3;
  int val = 0, test = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const std::string s = nsm_frame_split(p, i);
    val += s == "val";
    test += s == "test";
  }
  // Binomial: 4 standard deviations.
  EXPECT_NEAR(val, 0.2 * n, 4 * std::sqrt(n * 0.2 * 0.8));
  EXPECT_NEAR(test, 0.3 * n, 4 * std::sqrt(n * 0.3 * 0.7));
  p.scenes = {"default", "plane"};
  p.test = {{"plane"}, 0.0};
  p.val = {{}, 0.0};
  for (int i = 0; i < 10; ++i) EXPECT_EQ(nsm_frame_split(p, i), i % 2 ? "test" : "train");
}

}  // namespace nsm_dataset_test
}  // namespace shadowlab
