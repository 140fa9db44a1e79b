// The data set's random choices (lab/nsm_dataset.h) against their stated bounds: the perturbed
// copies' light offsets within the ball and reaching its edge, the camera's within 0.5 px at
// the target's depth with eye and target moved together, crops inside the frame, splits.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "lab/nsm_dataset.h"
#include "scenes/scene_registry.h"
#include "test_paths.h"
#include "tests/worst_of.h"

namespace shadowlab {
// A named namespace: the unity build compiles several test files in one translation unit.
namespace nsm_dataset_test {

// The file hash is the last 8 bytes, little-endian, for any input of at least 8 bytes.
TEST(NsmDataset, FileHashIsTheLastEightBytes) {
  EXPECT_EQ(nsm_file_hash(std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8)), 0x0807060504030201ull);
  EXPECT_EQ(nsm_file_hash(std::string("xyz\x10\0\0\0\0\0\0\xff", 11)), 0xff00000000000010ull);
}

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
      max_light = test::worst_of(max_light, double(dl / ball));
      const vec3 de = s.camera.eye - s0.camera.eye, dt = s.camera.target - s0.camera.target;
      EXPECT_NEAR(glm::length(de - dt), 0.0, 1e-5);
      // In the image plane: perpendicular to the view direction.
      EXPECT_NEAR(glm::dot(de, glm::normalize(s0.camera.target - s0.camera.eye)), 0.0, 1e-5);
      const long double dc = glm::length(de);
      EXPECT_LE(dc, 0.5L * pixel * (1 + 1e-4L) + 1e-6L) << frame << " " << c;
      max_cam = test::worst_of(max_cam, double(dc / pixel));
    }
  }
  // 120 uniform draws in the ball reach past 0.8 of its radius (P(miss) = 0.512^120), and in
  // the disk past 0.4 px (P(miss) = 0.64^120).
  EXPECT_GT(max_light, 0.8);
  EXPECT_GT(max_cam, 0.4);
}

TEST(NsmDataset, TrajectoriesStayWithinTheirStatedRanges) {
  // The camera's eye orbits the vertical through its target by up to ±40° at 0.85–1.15× its
  // distance (docs/programs/nsm_data.md). 300 uniform draws reach past 39° (P(miss) =
  // (39/40)^300 = 5e-4) and within 0.01 of each end of the distance range ((1 − 0.01/0.3)^300
  // = 4e-5), so a range 1° or 0.01 too narrow fails as surely as one too wide.
  NsmDatasetParams p;
  const Scene base = make_builtin_scene("default");
  const vec3 t = base.camera.target;
  const long double base_r = glm::length(base.camera.eye - t);
  const long double a0 = std::atan2((long double)(base.camera.eye.x - t.x), (long double)(base.camera.eye.z - t.z));
  double max_angle = 0.0, min_scale = 2.0, max_scale = 0.0;
  for (int frame = 0; frame < 300; ++frame) {
    const Scene s = nsm_frame_scene(base, p, frame);
    const vec3 e = s.camera.eye - s.camera.target;
    long double a = std::atan2((long double)e.x, (long double)e.z) - a0;
    while (a > 3.14159265358979323846L) a -= 2 * 3.14159265358979323846L;
    while (a < -3.14159265358979323846L) a += 2 * 3.14159265358979323846L;
    const double deg = double(std::fabs(a) * 180.0L / 3.14159265358979323846L);
    EXPECT_LE(deg, 40.0 + 1e-3) << frame;
    max_angle = test::worst_of(max_angle, deg);
    const double scale = double(glm::length(e) / base_r);
    EXPECT_GE(scale, 0.85 - 1e-5) << frame;
    EXPECT_LE(scale, 1.15 + 1e-5) << frame;
    min_scale = std::min(min_scale, scale);
    max_scale = test::worst_of(max_scale, scale);
  }
  EXPECT_GT(max_angle, 39.0);
  EXPECT_LT(min_scale, 0.86);
  EXPECT_GT(max_scale, 1.14);
}

// The light turns about the vertical through the camera's target by up to ±30° at 0.9–1.1× its
// distance, unless the turned light would not fit the scene (then it keeps the scene's place).
// 3,000 frames: each side of the range is reached past 29° (with ~1,300 turned frames a side,
// P(miss) = (59/60)^1300 = 3e-10), so a range 1° short on either side fails.
TEST(NsmDataset, TheLightTurnsWithinItsStatedRange) {
  NsmDatasetParams p;
  const Scene base = make_builtin_scene("default");
  const vec3 t = base.camera.target, l0 = base.light.position - t;
  const long double a0 = std::atan2((long double)l0.x, (long double)l0.z);
  const double r0 = std::hypot(double(l0.x), double(l0.z));
  double max_deg = 0.0, min_deg = 0.0;
  int turned = 0;
  for (int frame = 0; frame < 3000; ++frame) {
    const vec3 l = nsm_frame_scene(base, p, frame).light.position - t;
    if (l == l0) continue;  // kept: the turned light did not fit
    ++turned;
    long double a = std::atan2((long double)l.x, (long double)l.z) - a0;
    while (a > 3.14159265358979323846L) a -= 2 * 3.14159265358979323846L;
    while (a < -3.14159265358979323846L) a += 2 * 3.14159265358979323846L;
    const double deg = double(a * 180.0L / 3.14159265358979323846L);
    EXPECT_LE(std::fabs(deg), 30.0 + 1e-3) << frame;
    max_deg = test::worst_of(max_deg, deg);
    min_deg = std::min(min_deg, deg);
    const double reach = std::hypot(double(l.x), double(l.z)) / r0;
    EXPECT_GE(reach, 0.9 - 1e-5) << frame;
    EXPECT_LE(reach, 1.1 + 1e-5) << frame;
  }
  EXPECT_GT(turned, 2000);
  EXPECT_GT(max_deg, 29.0);
  EXPECT_LT(min_deg, -29.0);
}

// A data set of small frames, a crop of crop_w × crop_h, one ray per pixel at one radius (the
// files' layout and the writer's messages, not the data's quality).
NsmDatasetParams tiny_params(int frames, int width, int height, int crop_w, int crop_h) {
  NsmDatasetParams p;
  p.frames = frames;
  p.width = width;
  p.height = height;
  p.crop_w = crop_w;
  p.crop_h = crop_h;
  p.spp = 1;
  p.base_res = 32;
  p.radii = {0.0};
  return p;
}

// docs/programs/nsm_data.md: a frame file is its header, zero padding to a multiple of 64, the
// planes each starting at a multiple of 64, then the 8-byte hash: the length before the hash
// is a multiple of 64, whatever the crop's size.
TEST(NsmDataset, FrameFilesKeepTheir64ByteLayout) {
  // Planes of 13 × 7 floats: 364 bytes, not a multiple of 64.
  NsmDatasetParams p = tiny_params(1, 24, 20, 13, 7);
  check_nsm_dataset_params(p);
  const std::string bytes = nsm_frame_file(p, make_builtin_scene("default"), 0);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ((bytes.size() - 8) % 64, 0u) << bytes.size();
  // "NSMF", version, header length H, H bytes of JSON, then zeros up to the first plane.
  ASSERT_EQ(bytes.substr(0, 4), "NSMF");
  const uint32_t h = uint32_t(uint8_t(bytes[8])) | uint32_t(uint8_t(bytes[9])) << 8 |
                     uint32_t(uint8_t(bytes[10])) << 16 | uint32_t(uint8_t(bytes[11])) << 24;
  const size_t end = 12 + size_t(h), first_plane = (end + 63) / 64 * 64;
  ASSERT_EQ(bytes[12], '{');
  ASSERT_EQ(bytes[end - 1], '}');
  for (size_t i = end; i < first_plane; ++i) ASSERT_EQ(bytes[i], '\0') << i;
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

// The progress counter counts the frames written, from 1/N to N/N, and ends its line.
TEST(NsmDataset, ProgressCountsFromOneToTheFrameCount) {
  NsmDatasetParams p = tiny_params(2, 32, 24, 16, 12);
  p.val = {{}, 0.0};
  p.test = {{}, 0.0};
  check_nsm_dataset_params(p);
  const std::string dir = test::binary_path("nsm_dataset_progress");
  std::filesystem::remove_all(dir);
  testing::internal::CaptureStderr();
  write_nsm_dataset(p, dir, {"nsm_data"}, true);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "\rnsm_data: frame 1/2\rnsm_data: frame 2/2\n");
}

}  // namespace nsm_dataset_test
}  // namespace shadowlab
