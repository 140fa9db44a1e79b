// LDR-FLIP (metric/flip.h) on properties with known answers, and against a brute force written
// here straight from the paper's equations: 2D kernels evaluated and normalized as 2D sums,
// every tap read with clamped coordinates, in long double.
#include "metric/flip.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "tests/worst_of.h"

namespace shadowlab {
namespace {

using LD = long double;
constexpr LD kPiL = 3.14159265358979323846264338327950288L;

// ---- the brute force ----------------------------------------------------------------------

struct C3 {
  LD a, b, c;
};

C3 rgb_to_xyz(C3 v) {
  return {(10135552.0L * v.a + 8788810.0L * v.b + 4435075.0L * v.c) / 24577794.0L,
          (2613072.0L * v.a + 8788810.0L * v.b + 887015.0L * v.c) / 12288897.0L,
          (1425312.0L * v.a + 8788810.0L * v.b + 70074185.0L * v.c) / 73733382.0L};
}
C3 xyz_to_rgb(C3 v) {
  return {3.241003275L * v.a - 1.537398934L * v.b - 0.498615861L * v.c,
          -0.969224334L * v.a + 1.875930071L * v.b + 0.041554224L * v.c,
          0.055639423L * v.a - 0.204011202L * v.b + 1.057148933L * v.c};
}
constexpr LD kWx = 0.950428545L, kWz = 1.088900371L, kIWx = 1.052156925L, kIWz = 0.918357670L;

C3 lin_to_ycc(C3 rgb) {
  const C3 x = rgb_to_xyz(rgb);
  const LD X = x.a * kIWx, Y = x.b, Z = x.c * kIWz;
  return {116 * Y - 16, 500 * (X - Y), 200 * (Y - Z)};
}
C3 ycc_to_lin(C3 c) {
  const LD Y = (c.a + 16) / 116;
  return xyz_to_rgb({(Y + c.b / 500) * kWx, Y, (Y - c.c / 200) * kWz});
}
C3 hunt_lab(C3 rgb) {
  const C3 x = rgb_to_xyz(rgb);
  const LD d = 6.0L / 29.0L;
  auto f = [&](LD t) { return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0L / 29.0L; };
  const LD fx = f(x.a * kIWx), fy = f(x.b), fz = f(x.c * kIWz);
  const LD L = 116 * fy - 16;
  return {L, L / 100 * 500 * (fx - fy), L / 100 * 200 * (fy - fz)};
}
LD hyab(C3 p, C3 q) {
  return std::fabs(p.a - q.a) + std::sqrt((p.b - q.b) * (p.b - q.b) + (p.c - q.c) * (p.c - q.c));
}
LD cmax_bf() { return std::pow(hyab(hunt_lab({0, 1, 0}), hunt_lab({0, 0, 1})), 0.7L); }
LD colour_error(LD de, LD cmax) {
  const LD e = std::pow(de, 0.7L), knee = 0.4L * cmax;
  return e < knee ? 0.95L / knee * e : 0.95L + (e - knee) / (cmax - knee) * 0.05L;
}

// 2D correlation with a (2r+1)² kernel, clamp-to-edge.
std::vector<LD> correlate2d(const std::vector<LD>& in, int w, int h, const std::vector<LD>& k,
                            int r) {
  std::vector<LD> out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      LD s = 0;
      for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i)
          s += k[size_t((j + r) * (2 * r + 1) + i + r)] *
               in[size_t(std::clamp(y + j, 0, h - 1) * w + std::clamp(x + i, 0, w - 1))];
      out[size_t(y * w + x)] = s;
    }
  return out;
}

// Paper eq. 2: s(x, y) = a1·√(π/b1)·e^(−π²d²/b1) + a2·√(π/b2)·e^(−π²d²/b2), d in degrees,
// over 3 standard deviations of the widest (b = 0.04), normalized to sum 1.
std::vector<LD> csf2d(LD a1, LD b1, LD a2, LD b2, LD ppd, int& r) {
  r = int(std::ceil(3 * std::sqrt(0.04L / (2 * kPiL * kPiL)) * ppd));
  std::vector<LD> k;
  LD sum = 0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      const LD d2 = (LD(x) * x + LD(y) * y) / (ppd * ppd);
      const LD v = a1 * std::sqrt(kPiL / b1) * std::exp(-kPiL * kPiL * d2 / b1) +
                   a2 * std::sqrt(kPiL / b2) * std::exp(-kPiL * kPiL * d2 / b2);
      k.push_back(v);
      sum += v;
    }
  for (LD& v : k) v /= sum;
  return k;
}

// Edge (−x·g) or point ((x²/σ² − 1)·g) detector across x, σ = ½·0.082·ppd, radius 3σ; positive
// weights scaled to sum 1, negative ones to −1. `transpose`: across y.
std::vector<LD> feature2d(LD ppd, bool point, bool transpose, int& r) {
  const LD sd = 0.5L * 0.082L * ppd;
  r = int(std::ceil(3 * sd));
  std::vector<LD> k;
  LD pos = 0, neg = 0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      const LD u = transpose ? y : x;
      const LD g = std::exp(-(LD(x) * x + LD(y) * y) / (2 * sd * sd));
      const LD v = point ? (u * u / (sd * sd) - 1) * g : -u * g;
      k.push_back(v);
      (v > 0 ? pos : neg) += v;
    }
  for (LD& v : k) v = v > 0 ? v / pos : v / -neg;
  return k;
}

struct Prep {
  std::vector<C3> lab;
  std::vector<LD> edge, point;
};

Prep prepare_bf(const ImageF& img, LD ppd) {
  const int w = img.width, h = img.height;
  const size_t n = img.pixel_count();
  std::vector<LD> ycc[3];
  for (size_t i = 0; i < n; ++i) {
    auto v = [&](int c) {
      return std::clamp(LD(img.data[size_t(img.channels == 3 ? c : 0) * n + i]), LD(0), LD(1));
    };
    const C3 c = lin_to_ycc({v(0), v(1), v(2)});
    ycc[0].push_back(c.a);
    ycc[1].push_back(img.channels == 1 ? 0 : c.b);  // a grey image is achromatic (metric/flip.h)
    ycc[2].push_back(img.channels == 1 ? 0 : c.c);
  }
  const LD params[3][4] = {
      {1, 0.0047L, 0, 1e-5L}, {1, 0.0053L, 0, 1e-5L}, {34.1L, 0.04L, 13.5L, 0.025L}};
  std::vector<LD> f[3];
  for (int c = 0; c < 3; ++c) {
    int r = 0;
    const std::vector<LD> k = csf2d(params[c][0], params[c][1], params[c][2], params[c][3], ppd, r);
    f[c] = correlate2d(ycc[c], w, h, k, r);
  }
  Prep p;
  for (size_t i = 0; i < n; ++i) {
    if (img.channels == 1) {  // a grey stays grey: L* of the clamped luminance, a* = b* = 0
      const LD Y = std::clamp((f[0][i] + 16) / 116, LD(0), LD(1)), d = 6.0L / 29.0L;
      const LD fy = Y > d * d * d ? std::cbrt(Y) : Y / (3 * d * d) + 4.0L / 29.0L;
      p.lab.push_back({116 * fy - 16, 0, 0});
      continue;
    }
    C3 rgb = ycc_to_lin({f[0][i], f[1][i], f[2][i]});
    rgb = {std::clamp(rgb.a, LD(0), LD(1)), std::clamp(rgb.b, LD(0), LD(1)),
           std::clamp(rgb.c, LD(0), LD(1))};
    p.lab.push_back(hunt_lab(rgb));
  }
  std::vector<LD> lum(n);
  for (size_t i = 0; i < n; ++i) lum[i] = (ycc[0][i] + 16) / 116;
  for (const bool point : {false, true}) {
    int r = 0;
    const std::vector<LD> kx = feature2d(ppd, point, false, r), ky = feature2d(ppd, point, true, r);
    const std::vector<LD> fx = correlate2d(lum, w, h, kx, r), fy = correlate2d(lum, w, h, ky, r);
    std::vector<LD>& m = point ? p.point : p.edge;
    for (size_t i = 0; i < n; ++i) m.push_back(std::sqrt(fx[i] * fx[i] + fy[i] * fy[i]));
  }
  return p;
}

std::vector<LD> flip_bf(const ImageF& test, const ImageF& ref, LD ppd) {
  const Prep t = prepare_bf(test, ppd), r = prepare_bf(ref, ppd);
  const LD cm = cmax_bf();
  std::vector<LD> out;
  for (size_t i = 0; i < test.pixel_count(); ++i) {
    const LD dc = colour_error(hyab(r.lab[i], t.lab[i]), cm);
    const LD dfr = std::max(std::fabs(r.edge[i] - t.edge[i]), std::fabs(r.point[i] - t.point[i]));
    out.push_back(std::pow(dc, 1 - std::pow(dfr / std::sqrt(LD(2)), 0.5L)));
  }
  return out;
}

// ---- images -------------------------------------------------------------------------------

ImageF flat(int w, int h, float r, float g, float b) {
  ImageF im(w, h, 3);
  std::fill(im.plane(0), im.plane(0) + im.pixel_count(), r);
  std::fill(im.plane(1), im.plane(1) + im.pixel_count(), g);
  std::fill(im.plane(2), im.plane(2) + im.pixel_count(), b);
  return im;
}

// A shadow-like mask: a soft-edged disc, a hard step and noise.
ImageF mask_scene(int w, int h, unsigned seed, float shift) {
  ImageF im(w, h, 1);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 0.08f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float d = std::hypot(float(x) - 0.4f * w - shift, float(y) - 0.5f * h) / (0.25f * w);
      float v = std::clamp(1.5f * (d - 0.7f), 0.0f, 1.0f);
      if (x > 3 * w / 4) v *= 0.3f;
      im.at(x, y) = std::clamp(v + u(rng), 0.0f, 1.0f);
    }
  return im;
}

TEST(Flip, SrgbDecodeIsTheStandardsPiecewiseCurve) {
  // IEC 61966-2-1: v / 12.92 up to 0.04045, ((v + 0.055) / 1.055)^2.4 above; the values are
  // those formulas evaluated in Python (float64).
  EXPECT_EQ(srgb_to_linear(0.0), 0.0);
  EXPECT_NEAR(srgb_to_linear(0.04), 0.0030959752321981426, 1e-17);
  EXPECT_NEAR(srgb_to_linear(0.04045), 0.0031308049535603713, 1e-17);   // the linear side
  EXPECT_NEAR(srgb_to_linear(0.040451), 0.0031308860048338896, 1e-15);  // the power side
  EXPECT_NEAR(srgb_to_linear(0.5), 0.21404114048223255, 1e-15);
  EXPECT_NEAR(srgb_to_linear(1.0), 1.0, 1e-15);
}

TEST(Flip, IdenticalImagesGiveZero) {
  const ImageF a = mask_scene(48, 36, 1, 0.0f);
  const ImageF e = flip_error_map(a, a);
  for (float v : e.data) ASSERT_EQ(v, 0.0f);
  EXPECT_EQ(flip_mean(e), 0.0);
}

// Two flat images: the filters leave a constant image unchanged and find no feature in it, so
// every pixel's FLIP is the redistributed colour error of the two colours. By hand, grey 0.5
// against 0.25 (linear): L* = 116·∛Y − 16 = 76.07 and 57.08, a* = b* = 0, HyAB 18.99,
// 18.99^0.7 = 7.85; cmax: green (L 87.73, a −86.18, b 83.18) against blue (32.30, 79.19,
// −107.86), Hunt-adjusted, HyAB 203.3, ^0.7 = 41.27; 7.85 < 0.4·41.27, so FLIP = 0.95·7.85 /
// (0.4·41.27) = 0.452. The brute force gives the same colour error to full precision.
TEST(Flip, UniformShiftIsTheHandComputedColourError) {
  const ImageF a = flat(24, 20, 0.5f, 0.5f, 0.5f), b = flat(24, 20, 0.25f, 0.25f, 0.25f);
  const ImageF e = flip_error_map(b, a);
  EXPECT_NEAR(e.data[0], 0.452, 0.002);  // the hand computation's rounding
  const LD want =
      colour_error(hyab(hunt_lab({0.5L, 0.5L, 0.5L}), hunt_lab({0.25L, 0.25L, 0.25L})), cmax_bf());
  for (float v : e.data) ASSERT_NEAR(v, double(want), 1e-7);
  // A colour shift too (red against orange): the same rule.
  const ImageF c = flat(24, 20, 0.8f, 0.1f, 0.1f), d = flat(24, 20, 0.8f, 0.4f, 0.1f);
  const LD want2 =
      colour_error(hyab(hunt_lab({0.8L, 0.1L, 0.1L}), hunt_lab({0.8L, 0.4L, 0.1L})), cmax_bf());
  const ImageF e2 = flip_error_map(d, c);
  for (float v : e2.data) ASSERT_NEAR(v, double(want2), 1e-7);
  // Black against white: an error above the knee p_c·c_max, mapped onto [p_t, 1].
  const LD want3 =
      colour_error(hyab(hunt_lab({0.0L, 0.0L, 0.0L}), hunt_lab({1.0L, 1.0L, 1.0L})), cmax_bf());
  ASSERT_GT(want3, 0.95L);
  for (float v : flip_error_map(flat(24, 20, 0, 0, 0), flat(24, 20, 1, 1, 1)).data)
    ASSERT_NEAR(v, double(want3), 1e-7);
}

// Dark colours, whose XYZ lie below CIELAB's knee (6/29)³ where f(t) = t / (3·(6/29)²) + 4/29:
// the colour error against the brute force. Hunt's a and b scale with L, so an offset in f,
// which cancels in ΔL, shows in them.
TEST(Flip, DarkColoursFollowCielabsLinearSegment) {
  const C3 pairs[][2] = {{{0.004L, 0.001L, 0.0L}, {0.0L, 0.002L, 0.004L}},
                         {{0.0L, 0.0L, 0.0L}, {0.006L, 0.0L, 0.003L}},
                         {{0.002L, 0.003L, 0.001L}, {0.03L, 0.01L, 0.02L}}};
  for (const auto& p : pairs) {
    const LD want = colour_error(hyab(hunt_lab(p[1]), hunt_lab(p[0])), cmax_bf());
    const ImageF e = flip_error_map(flat(24, 20, float(p[1].a), float(p[1].b), float(p[1].c)),
                                    flat(24, 20, float(p[0].a), float(p[0].b), float(p[0].c)));
    ASSERT_GT(want, 0.01L);
    for (float v : e.data) ASSERT_NEAR(v, double(want), 1e-6) << double(p[1].a);
  }
}

// A grey image and its three-channel copy are the same picture (the grey path and the colour
// path give the same CIELAB), so FLIP between them is 0 everywhere; and the error map has the
// images' width and height.
TEST(Flip, AGreyImageAndItsColourCopyAgree) {
  const ImageF grey = mask_scene(40, 30, 3, 0.0f);
  ImageF colour(40, 30, 3);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      for (int c = 0; c < 3; ++c) colour.data[size_t(c) * 1200 + size_t(y) * 40 + size_t(x)] = grey.at(x, y);
  const ImageF e = flip_error_map(colour, grey);
  EXPECT_EQ(e.width, 40);
  EXPECT_EQ(e.height, 30);
  EXPECT_EQ(e.channels, 1);
  for (float v : e.data) ASSERT_LT(v, 5e-5f);  // the two paths round differently: measured 1.1e-5
  const ImageF f = flip_error_map(mask_scene(40, 30, 4, 1.5f), grey);
  EXPECT_EQ(f.width, 40);
  EXPECT_EQ(f.height, 30);
}

// The default observer: a 3840-pixel-wide monitor 0.7 m wide seen from 0.7 m, FLIP's default
// (Andersson et al. 2020: 67 pixels per degree): 3840 · π / 180 = 67.0206.
TEST(Flip, DefaultObserverSees67PixelsPerDegree) { EXPECT_NEAR(kFlipPixelsPerDegree, 67.0206, 1e-4); }

TEST(Flip, MeanIsThePlainMeanOfTheMap) {
  ImageF m(3, 2, 1);
  for (int i = 0; i < 6; ++i) m.data[size_t(i)] = float(i);  // 0..5: rows differ, columns differ
  EXPECT_EQ(flip_mean(m), 2.5);
  EXPECT_EQ(flip_mean(ImageF()), 0.0);
}

// A flat region's value does not depend on the image's size: every pixel of a 30 × 30 and of a
// 90 × 60 image pair holds the same bits.
TEST(Flip, FlatRegionsAreSizeInvariant) {
  const ImageF e1 = flip_error_map(flat(30, 30, 0.2f, 0.6f, 0.3f), flat(30, 30, 0.3f, 0.5f, 0.3f));
  const ImageF e2 = flip_error_map(flat(90, 60, 0.2f, 0.6f, 0.3f), flat(90, 60, 0.3f, 0.5f, 0.3f));
  for (float v : e1.data) ASSERT_EQ(v, e1.data[0]);
  for (float v : e2.data) ASSERT_EQ(v, e1.data[0]);
  EXPECT_GT(e1.data[0], 0.0f);
}

// The separable passes against the 2D brute force, on masks (grey) and colour images, at the
// default observer and a nearer one (smaller kernels).
TEST(Flip, SeparableFiltersMatchTheEquationsBruteForce) {
  double worst = 0.0;
  for (const double ppd : {kFlipPixelsPerDegree, 20.0}) {
    const ImageF a = mask_scene(40, 30, 3, 0.0f), b = mask_scene(40, 30, 4, 1.5f);
    ImageF ca(40, 30, 3), cb(40, 30, 3);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (size_t i = 0; i < ca.data.size(); ++i) {
      ca.data[i] = u(rng);
      cb.data[i] = std::clamp(ca.data[i] + 0.3f * (u(rng) - 0.5f), 0.0f, 1.0f);
    }
    for (const auto& [t, r] : {std::pair<const ImageF*, const ImageF*>{&b, &a},
                               std::pair<const ImageF*, const ImageF*>{&cb, &ca}}) {
      const ImageF e = flip_error_map(*t, *r, ppd);
      const std::vector<LD> want = flip_bf(*t, *r, ppd);
      for (size_t i = 0; i < want.size(); ++i)
        worst = test::worst_of(worst, double(std::fabs(LD(e.data[i]) - want[i])));
    }
  }
  RecordProperty("worst_abs_error", fmt::format("{:.3g}", worst));
  EXPECT_LE(worst, 1e-7);  // float output: half an ulp of values below 1 is 6e-8
}

TEST(Flip, SameBitsAtAnyThreadCount) {
  const ImageF a = mask_scene(64, 48, 5, 0.0f), b = mask_scene(64, 48, 6, 2.0f);
  const int saved = thread_count();
  set_thread_count(1);
  const ImageF e1 = flip_error_map(b, a);
  set_thread_count(2);
  const ImageF e2 = flip_error_map(b, a);
  set_thread_count(7);
  const ImageF e7 = flip_error_map(b, a);
  set_thread_count(saved);
  EXPECT_EQ(e1.data, e2.data);
  EXPECT_EQ(e1.data, e7.data);
}

TEST(Flip, BadInputIsRejected) {
  const ImageF a(8, 8, 1), b(9, 8, 1), two(8, 8, 2);
  EXPECT_THROW(flip_error_map(a, b), InputError);
  EXPECT_THROW(flip_error_map(two, two), InputError);
  ImageF nan(8, 8, 1);
  nan.data[3] = std::nanf("");
  EXPECT_THROW(flip_error_map(nan, a), InputError);
  EXPECT_THROW(flip_error_map(a, a, 0.0), InputError);
  EXPECT_THROW(flip_error_map(a, a, 0.5), InputError);  // the edge detector would be 0/0
  for (float v : flip_error_map(mask_scene(8, 8, 2, 0.0f), a, 1.0).data) ASSERT_TRUE(std::isfinite(v));
  EXPECT_THROW(flip_error_map(ImageF(), ImageF()), InputError);
  // One empty image is named as such, not as a size mismatch.
  for (const bool test_empty : {true, false}) {
    try {
      flip_error_map(test_empty ? ImageF() : a, test_empty ? a : ImageF());
      ADD_FAILURE() << test_empty;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("empty image"), std::string::npos) << e.what();
    }
  }
  // The observer's range is [1, 1000] pixels per degree, both ends included.
  EXPECT_NO_THROW(flip_error_map(a, a, 1.0));
  EXPECT_NO_THROW(flip_error_map(a, a, 1000.0));
  EXPECT_THROW(flip_error_map(a, a, 1000.5), InputError);
}

}  // namespace
}  // namespace shadowlab
