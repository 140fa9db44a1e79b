// The slide projector (core/projector.h) and its slides (core/slide.h): projective lookup
// against hand-computed frames, the frustum gate, perspective correctness, the procedural
// slides' analytic values, slide specs and files, and validation.
#include "core/projector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "core/error.h"
#include "core/image_io.h"
#include "core/slide.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Expects fn() to throw an InputError whose `where` is exactly `where`.
template <class Fn>
void expect_input_error_at(Fn&& fn, const std::string& where, const std::string& what) {
  try {
    fn();
    ADD_FAILURE() << what << ": no InputError thrown (expected one naming '" << where << "')";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, where) << what << ": message '" << e.what() << "'";
  }
}

// Slide of W × H texels, every texel distinct: value (y·W + x + 1)/(W·H) in all channels
// (all > 0, so "lit" and "no light" are told apart; neighbours differ by ≥ 1/(W·H)).
ImageF distinct_slide(int w, int h) {
  ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(y * w + x + 1) / float(w * h);
  return img;
}

// The frame of core/projector.h's header, computed independently in double precision:
// forward = normalize(direction), right = normalize(forward × up), up' = right × forward,
// tan_y = tan(fov_y/2), tan_x = aspect·tan_y.
struct HandFrame {
  glm::dvec3 position, forward, right, up;
  double tan_x, tan_y;
};
HandFrame hand_frame(const Projector& p) {
  HandFrame f;
  f.position = glm::dvec3(p.position);
  f.forward = glm::normalize(glm::dvec3(p.direction));
  f.right = glm::normalize(glm::cross(f.forward, glm::dvec3(p.up)));
  f.up = glm::cross(f.right, f.forward);
  f.tan_y = std::tan(double(p.fov_y_deg) * kPi / 360.0);
  f.tan_x = double(p.aspect) * f.tan_y;
  return f;
}
// World point at distance `depth` along forward whose slide coordinates are (s, t): inverting
// s = ½ + ½·x/(z·tan_x), t = ½ − ½·y/(z·tan_y) gives x = (2s − 1)·z·tan_x, y = (1 − 2t)·z·tan_y.
vec3 point_at_st(const HandFrame& f, double s, double t, double depth) {
  const glm::dvec3 p = f.position + depth * f.forward + (2.0 * s - 1.0) * depth * f.tan_x * f.right +
                       (1.0 - 2.0 * t) * depth * f.tan_y * f.up;
  return vec3(p);
}

Projector hand_projector(int w, int h) {
  Projector p;
  p.enabled = true;
  p.position = vec3(1.0f, 2.0f, 3.0f);
  p.direction = vec3(0.3f, -0.5f, -1.0f);
  p.up = vec3(0.0f, 1.0f, 0.0f);
  p.fov_y_deg = 50.0f;
  p.aspect = 1.6f;
  p.slide.name = "distinct";
  p.slide.rgb = distinct_slide(w, h);
  return p;
}

// A point built to project to the centre of texel (x, y) has st = ((x + ½)/W, (y + ½)/H), and
// the light there is that texel's value (bilinear at a texel centre is the texel).
TEST(Projector, KnownPointLandsOnKnownTexel) {
  const int W = 8, H = 5;
  const Projector proj = hand_projector(W, H);
  const ProjectorFrame frame = projector_frame(proj);
  const HandFrame hf = hand_frame(proj);
  const int texels[][2] = {{0, 0}, {W - 1, 0}, {0, H - 1}, {W - 1, H - 1}, {3, 2}, {5, 1}, {2, 4}};
  for (const auto& xy : texels) {
    const int x = xy[0], y = xy[1];
    const double s = (x + 0.5) / W, t = (y + 0.5) / H;
    for (double depth : {0.3, 2.0, 7.5}) {
      const vec3 p = point_at_st(hf, s, t, depth);
      vec2 st;
      ASSERT_TRUE(projector_slide_coords(frame, proj.position, p, st)) << x << "," << y;
      EXPECT_NEAR(st.x, s, 1e-5) << "texel " << x << "," << y << " depth " << depth;
      EXPECT_NEAR(st.y, t, 1e-5) << "texel " << x << "," << y << " depth " << depth;
      // Within 1e-4 of the texel's value: far below the 1/(W·H) = 0.025 between neighbours.
      const float expected = float(y * W + x + 1) / float(W * H);
      const vec3 light = projector_light(proj, frame, p);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(light[c], expected, 1e-4) << "texel " << x << "," << y << " channel " << c;
    }
  }
  // The exact lookup: sample_slide at the texel centres, computed in float as the header
  // defines them, returns the texel itself.
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const vec3 v = sample_slide(proj.slide.rgb, vec2((x + 0.5f) / W, (y + 0.5f) / H));
      EXPECT_NEAR(v.x, float(y * W + x + 1) / float(W * H), 1e-6) << x << "," << y;
    }
}

// Nothing behind the projector (or in its plane, z = 0) is lit, and points just outside the
// frustum get no light while points just inside do.
TEST(Projector, NothingBehindOrOutsideIsLit) {
  const Projector proj = hand_projector(8, 5);
  const ProjectorFrame frame = projector_frame(proj);
  const HandFrame hf = hand_frame(proj);
  vec2 st;
  // The projector's own position and points exactly in its plane (z = 0 up to rounding;
  // a tiny positive rounding z puts them far outside the frustum instead).
  std::vector<vec3> pts = {proj.position, vec3(hf.position + 0.5 * hf.right),
                           vec3(hf.position - 0.7 * hf.up + 0.2 * hf.right)};
  const uint32_t seed = 12345;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-3.0, 3.0), back(1e-3, 5.0);
  for (int i = 0; i < 500; ++i)
    pts.push_back(vec3(hf.position - back(rng) * hf.forward + u(rng) * hf.right + u(rng) * hf.up));
  for (size_t i = 0; i < pts.size(); ++i) {
    const vec3& p = pts[i];
    ASSERT_LE(glm::dot(glm::dvec3(p) - hf.position, hf.forward), 1e-6) << "test point " << i;
    EXPECT_FALSE(projector_slide_coords(frame, proj.position, p, st)) << "seed " << seed << " point " << i;
    EXPECT_EQ(projector_light(proj, frame, p), vec3(0.0f)) << "seed " << seed << " point " << i;
  }
  // Just outside each edge of the frustum (st 1e-3 beyond it) → 0; just inside → the slide.
  const double e = 1e-3;
  const double outside[][2] = {{-e, 0.5}, {1 + e, 0.5}, {0.5, -e}, {0.5, 1 + e}, {-e, -e}, {1 + e, 1 + e}};
  for (const auto& o : outside) {
    const vec3 p = point_at_st(hf, o[0], o[1], 3.0);
    EXPECT_FALSE(projector_slide_coords(frame, proj.position, p, st)) << o[0] << "," << o[1];
    EXPECT_EQ(projector_light(proj, frame, p), vec3(0.0f)) << o[0] << "," << o[1];
  }
  const double inside[][2] = {{e, 0.5}, {1 - e, 0.5}, {0.5, e}, {0.5, 1 - e}};
  for (const auto& o : inside) {
    const vec3 p = point_at_st(hf, o[0], o[1], 3.0);
    EXPECT_TRUE(projector_slide_coords(frame, proj.position, p, st)) << o[0] << "," << o[1];
    EXPECT_GT(projector_light(proj, frame, p).x, 0.0f) << o[0] << "," << o[1];
  }
}

// Perspective correctness: every point of one ray from the projector has the same st,
// whatever its distance (st depends on the direction only).
TEST(Projector, PointsOnOneRayShareSlideCoordinates) {
  const Projector proj = hand_projector(8, 5);
  const ProjectorFrame frame = projector_frame(proj);
  const HandFrame hf = hand_frame(proj);
  const uint32_t seed = 777;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> st01(0.02, 0.98), dist(0.05, 20.0);
  for (int i = 0; i < 200; ++i) {
    const double s = st01(rng), t = st01(rng);
    const glm::dvec3 dir = glm::dvec3(point_at_st(hf, s, t, 1.0)) - hf.position;
    const double k1 = dist(rng), k2 = dist(rng);
    vec2 a, b;
    ASSERT_TRUE(projector_slide_coords(frame, proj.position, vec3(hf.position + k1 * dir), a));
    ASSERT_TRUE(projector_slide_coords(frame, proj.position, vec3(hf.position + k2 * dir), b));
    EXPECT_NEAR(a.x, b.x, 1e-5) << "seed " << seed << " ray " << i << " k " << k1 << " " << k2;
    EXPECT_NEAR(a.y, b.y, 1e-5) << "seed " << seed << " ray " << i << " k " << k1 << " " << k2;
  }
}

// spot: r = |2·st − 1| (distance from the centre over half the side); 1 for r ≤ 0.6,
// smoothstep down to 0 at r = 1 (0.5 at r = 0.8, the midpoint), 0 beyond and in the corners.
TEST(Slide, SpotProfileIsFlatCoreSmoothFalloffDarkOutside) {
  auto at = [](double r, double angle) {
    return vec2(float(0.5 + 0.5 * r * std::cos(angle)), float(0.5 + 0.5 * r * std::sin(angle)));
  };
  EXPECT_EQ(spot_profile(vec2(0.5f, 0.5f)), 1.0f);
  for (double angle : {0.0, 0.7, 2.0, 4.1, 5.5}) {
    for (double r : {0.0, 0.2, 0.45, 0.59}) EXPECT_EQ(spot_profile(at(r, angle)), 1.0f) << r << " " << angle;
    for (double r : {1.0001, 1.1, 1.4}) EXPECT_EQ(spot_profile(at(r, angle)), 0.0f) << r << " " << angle;
    EXPECT_NEAR(spot_profile(at(0.8, angle)), 0.5f, 1e-5) << angle;
    // Monotone non-increasing along the radius, strictly inside the falloff.
    float prev = 2.0f;
    for (int k = 0; k <= 130; ++k) {
      const double r = k * 0.01;
      const float v = spot_profile(at(r, angle));
      EXPECT_LE(v, prev) << "r " << r << " angle " << angle;
      if (r > 0.61 && r < 0.99) {
        EXPECT_LT(v, prev) << "r " << r << " angle " << angle;
      }
      prev = v;
    }
  }
  for (vec2 c : {vec2(0, 0), vec2(1, 0), vec2(0, 1), vec2(1, 1)}) EXPECT_EQ(spot_profile(c), 0.0f);
}

// m(x) = 1 − A·(1 − cos(2πF(x − ½)))/2: F = 0 gives cos 0 = 1, m = 1 for any A; A = 1 gives
// m = (1 + cos)/2, 0 where cos = −1 (x − ½ = ½/F) and 1 on the axis x = ½ (and a whole cycle away).
TEST(Slide, GridModulationZerosAndOnes) {
  for (float amp : {0.0f, 0.3f, 1.0f})
    for (vec2 st : {vec2(0.1f, 0.9f), vec2(0.5f, 0.5f), vec2(0.0f, 1.0f), vec2(0.37f, 0.61f)})
      EXPECT_EQ(grid_modulation(st, amp, 0.0f), 1.0f) << amp;
  for (float F : {1.0f, 4.0f, 7.0f}) {
    EXPECT_NEAR(grid_modulation(vec2(0.5f, 0.5f), 1.0f, F), 1.0f, 1e-6) << F;
    EXPECT_NEAR(grid_modulation(vec2(0.5f + 0.5f / F, 0.5f), 1.0f, F), 0.0f, 1e-6) << F;
    EXPECT_NEAR(grid_modulation(vec2(0.5f, 0.5f - 0.5f / F), 1.0f, F), 0.0f, 1e-6) << F;
    if (F > 1.0f) {
      EXPECT_NEAR(grid_modulation(vec2(0.5f + 1.0f / F, 0.5f), 1.0f, F), 1.0f, 1e-5) << F;
    }
    // Half depth: the dark line keeps 1 − A = 0.5.
    EXPECT_NEAR(grid_modulation(vec2(0.5f + 0.5f / F, 0.5f), 0.5f, F), 0.5f, 1e-6) << F;
  }
}

// grid with freq 0 multiplies the spot by exactly 1, so its bake is the spot's, bit for bit.
TEST(Slide, GridAtFrequencyZeroIsTheSpot) {
  const Slide grid = make_slide("grid:amp=1,freq=0", "--slide");
  const Slide spot = make_slide("spot", "--slide");
  ASSERT_EQ(grid.rgb.width, 512);  // the default bake size
  ASSERT_EQ(grid.rgb.height, 512);
  ASSERT_EQ(grid.rgb.channels, 3);
  ASSERT_EQ(grid.rgb.data.size(), spot.rgb.data.size());
  EXPECT_EQ(0, std::memcmp(grid.rgb.data.data(), spot.rgb.data.data(), spot.rgb.data.size() * sizeof(float)));
  // res= sets the bake size; texel (x, y) holds spot_profile at its centre.
  const Slide small = make_slide("spot:res=8", "--slide");
  ASSERT_EQ(small.rgb.width, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(small.rgb.at(x, y, 1), spot_profile(vec2((x + 0.5f) / 8.0f, (y + 0.5f) / 8.0f)));
}

TEST(Slide, BadSpecsThrowNamingTheFlag) {
  for (const char* spec : {"nosuch", "grid:freq=4", "grid:amp=1", "grid:amp=2,freq=4", "grid:amp=1,freq=-1",
                           "spot:res=3", "spot:res=5000", "spot:foo=1", "spot:", "grid:amp=x,freq=1",
                           "spot:amp=1"})
    expect_input_error_at([&] { make_slide(spec, "--slide"); }, "--slide", spec);
  const std::string missing = "/no/such/slide.png";
  expect_input_error_at([&] { make_slide(missing, "--slide"); }, missing, missing);
  const std::string missing_exr = "/no/such/slide.exr";
  expect_input_error_at([&] { make_slide(missing_exr, "--slide"); }, missing_exr, missing_exr);
}

// The sRGB transfer function (IEC 61966-2-1), written out independently of core/texture.
double srgb_encode(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

// An 8-bit PNG slide stores round(255·srgb(v)); decoded back to linear, its sRGB encoding is
// within half a code step (0.5/255) of the original's.
TEST(Slide, PngSlideRoundTripWithinHalfAnSrgbStep) {
  const int w = 7, h = 4;
  ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = float(std::pow((x * 3 + y * 5 + c * 11) % 29 / 28.0, 2.0));
  img.at(0, 0, 0) = 0.0f;
  img.at(1, 0, 0) = 1.0f;
  img.at(2, 0, 0) = 0.002f;  // linear segment of sRGB
  const std::string path = test::binary_path("core/slide_roundtrip.png");
  write_png_rgb(path, img);
  const Slide s = make_slide(path, "--slide");
  ASSERT_EQ(s.rgb.width, w);
  ASSERT_EQ(s.rgb.height, h);
  ASSERT_EQ(s.rgb.channels, 3);
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double a = srgb_encode(img.at(x, y, c)), b = srgb_encode(s.rgb.at(x, y, c));
        EXPECT_LE(std::fabs(a - b), 0.5 / 255.0 + 1e-5) << x << "," << y << " c" << c;
      }
  EXPECT_EQ(s.rgb.at(0, 0, 0), 0.0f);  // code 0 and code 255 decode exactly
  EXPECT_EQ(s.rgb.at(1, 0, 0), 1.0f);
}

// EXR stores float32 linear values: the slide is the written image, bit for bit.
TEST(Slide, ExrSlideRoundTripIsBitExact) {
  const int w = 5, h = 3;
  ImageF img(w, h, 3);
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = float(i) * 0.0371f + 1e-7f;
  img.data[4] = 3.5f;  // EXR slides may exceed 1
  const std::string path = test::binary_path("core/slide_roundtrip.exr");
  write_exr_rgb(path, img);
  const Slide s = make_slide(path, "--slide");
  ASSERT_EQ(s.rgb.width, w);
  ASSERT_EQ(s.rgb.height, h);
  ASSERT_EQ(s.rgb.channels, 3);
  ASSERT_EQ(s.rgb.data.size(), img.data.size());
  EXPECT_EQ(0, std::memcmp(s.rgb.data.data(), img.data.data(), img.data.size() * sizeof(float)));
  // A negative value is bad input naming the file.
  img.data[2] = -0.5f;
  const std::string neg = test::binary_path("core/slide_negative.exr");
  write_exr_rgb(neg, img);
  expect_input_error_at([&] { make_slide(neg, "--slide"); }, neg, "negative exr");
}

TEST(Projector, ValidateRejectsUnusableProjectors) {
  const Projector good = hand_projector(4, 4);
  EXPECT_NO_THROW(validate_projector(good, "--slide"));
  auto bad = [&](const char* what, auto&& edit) {
    Projector p = good;
    edit(p);
    expect_input_error_at([&] { validate_projector(p, "--slide"); }, "--slide", what);
  };
  bad("zero direction", [](Projector& p) { p.direction = vec3(0.0f); });
  bad("up parallel", [](Projector& p) { p.up = -2.0f * p.direction; });
  bad("fov 0", [](Projector& p) { p.fov_y_deg = 0.0f; });
  bad("fov 170", [](Projector& p) { p.fov_y_deg = 170.0f; });
  bad("aspect 0.01", [](Projector& p) { p.aspect = 0.01f; });
  bad("empty slide", [](Projector& p) { p.slide.rgb = ImageF(); });
  bad("nan position", [](Projector& p) { p.position.x = std::nanf(""); });
}

}  // namespace
}  // namespace shadowlab
