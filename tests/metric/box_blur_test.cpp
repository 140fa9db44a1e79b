#include "metric/box_blur.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/error.h"

namespace shadowlab {
namespace {

ImageF random_image(int w, int h, std::mt19937& rng) {
  ImageF img(w, h, 1);
  for (float& v : img.data) v = float(rng() % 1001) / 1000.0f;
  return img;
}

// The definition, literally: mean of the k×k clamped neighbourhood, in double.
double brute_blur(const ImageF& img, int k, int x, int y) {
  const int r = k / 2;
  double s = 0.0;
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i)
      s += img.at(std::clamp(x + i, 0, img.width - 1), std::clamp(y + j, 0, img.height - 1));
  return s / (double(k) * double(k));
}

TEST(BoxBlur, MatchesBruteForceOnRandomImages) {
  std::mt19937 rng(1234);
  const int sizes[][2] = {{1, 1}, {1, 7}, {7, 1}, {5, 3}, {17, 9}, {40, 31}};
  for (const auto& s : sizes) {
    const ImageF img = random_image(s[0], s[1], rng);
    for (const int k : {1, 3, 5, 11, 21, 41}) {
      const ImageD b = box_blur(img, k);
      ASSERT_EQ(b.width, s[0]);
      ASSERT_EQ(b.height, s[1]);
      for (int y = 0; y < s[1]; ++y)
        for (int x = 0; x < s[0]; ++x)
          ASSERT_NEAR(b.at(x, y), brute_blur(img, k, x, y), 1e-12)
              << s[0] << "x" << s[1] << " k " << k << " at " << x << "," << y;
    }
  }
}

TEST(BoxBlur, HandComputedRowWithClampedEdge) {
  // Row [1 0 0 0 0], k = 3: x = 0 sees (m0, m0, m1) = (1, 1, 0) → 2/3; x = 1 sees (1, 0, 0) → 1/3.
  // A one-row image repeats that row vertically, which leaves the row mean unchanged.
  ImageF img(5, 1, 1, 0.0f);
  img.at(0, 0) = 1.0f;
  const ImageD b = box_blur(img, 3);
  EXPECT_NEAR(b.at(0, 0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(b.at(1, 0), 1.0 / 3.0, 1e-15);
  EXPECT_EQ(b.at(2, 0), 0.0);
  EXPECT_EQ(b.at(4, 0), 0.0);
}

TEST(BoxBlur, ConstantImageBlursToItselfExactly) {
  // Sums of up to 121 copies of a float are exact in double, and 121·v/121 rounds back to v.
  ImageF img(30, 20, 1, 0.3f);
  const ImageD b = box_blur(img, 11);
  for (const double v : b.data) ASSERT_EQ(v, double(0.3f));
}

TEST(BoxBlur, KernelSizeAtReferenceAndOtherSizes) {
  // k = round-to-odd(11·√(W·H)/√(1024·768)).
  EXPECT_EQ(blur_kernel_size(1024, 768), 11);
  EXPECT_EQ(blur_kernel_size(512, 384), 5);     // 11/2 = 5.5 → 2·2 + 1
  EXPECT_EQ(blur_kernel_size(256, 192), 3);     // 11/4 = 2.75 → 2·1 + 1
  EXPECT_EQ(blur_kernel_size(2048, 1536), 23);  // 22 → 2·11 + 1
  EXPECT_EQ(blur_kernel_size(64, 48), 1);       // 0.6875 → max(1, 1)
  EXPECT_EQ(blur_kernel_size(1920, 1080), 17);  // 11·1440/886.81 = 17.86 → 2·8 + 1
  EXPECT_EQ(blur_kernel_size(768, 1024), 11);   // 11·1 → 11, same area
}

TEST(BoxBlur, RoundToOdd) {
  EXPECT_EQ(round_to_odd(0.3), 1);
  EXPECT_EQ(round_to_odd(-5.0), 1);
  EXPECT_EQ(round_to_odd(2.0), 3);
  EXPECT_EQ(round_to_odd(10.99), 11);
  EXPECT_EQ(round_to_odd(11.0), 11);
  EXPECT_EQ(round_to_odd(12.0), 13);
}

TEST(BoxBlur, RejectsBadInput) {
  ImageF img(4, 4, 1, 0.5f);
  EXPECT_THROW(box_blur(img, 2), InputError);
  EXPECT_THROW(box_blur(img, 0), InputError);
  EXPECT_THROW(box_blur(ImageF(4, 4, 2), 3), InputError);
  EXPECT_THROW(blur_kernel_size(0, 5), InputError);
}

}  // namespace
}  // namespace shadowlab
