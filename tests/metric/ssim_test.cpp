#include "metric/ssim.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"
#include "metric/image_error.h"

namespace shadowlab {
namespace {

// Two constant images a, b: every window has σ = 0, so SSIM = (2ab + C1)/(a² + b² + C1).
double constant_pair_ssim(double a, double b) {
  const double c1 = 0.01 * 0.01;
  return (2 * a * b + c1) / (a * a + b * b + c1);
}

// Wang et al.'s definition written out in long double: an 11 × 11 window of weights
// exp(−(dx² + dy²) / (2·1.5²)) normalized to sum 1, the weighted means, variances and covariance
// of every valid window (wholly inside; clamp-to-edge reads along a dimension shorter than 11),
// SSIM per window from C1 = 0.01², C2 = 0.03², and their plain mean.
long double ssim_brute_force(const ImageF& a, const ImageF& b) {
  using LD = long double;
  LD w[11][11], sum = 0;
  for (int j = 0; j < 11; ++j)
    for (int i = 0; i < 11; ++i) sum += w[j][i] = std::exp(-LD((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2 * 1.5L * 1.5L));
  auto range = [](int n) { return n >= 11 ? std::pair{5, n - 5} : std::pair{0, n}; };
  const auto [x0, x1] = range(a.width);
  const auto [y0, y1] = range(a.height);
  LD total = 0;
  int windows = 0;
  for (int cy = y0; cy < y1; ++cy)
    for (int cx = x0; cx < x1; ++cx) {
      LD ma = 0, mb = 0, saa = 0, sbb = 0, sab = 0;
      for (int j = 0; j < 11; ++j)
        for (int i = 0; i < 11; ++i) {
          const int x = std::clamp(cx + i - 5, 0, a.width - 1), y = std::clamp(cy + j - 5, 0, a.height - 1);
          const LD k = w[j][i] / sum, p = a.at(x, y), q = b.at(x, y);
          ma += k * p;
          mb += k * q;
          saa += k * p * p;
          sbb += k * q * q;
          sab += k * p * q;
        }
      const LD va = saa - ma * ma, vb = sbb - mb * mb, cov = sab - ma * mb;
      const LD c1 = 1e-4L, c2 = 9e-4L;
      total += (2 * ma * mb + c1) * (2 * cov + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
      ++windows;
    }
  return total / windows;
}

TEST(Ssim, MatchesTheDefinitionBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (const auto& [w, h] : {std::pair{23, 17}, std::pair{14, 8}, std::pair{6, 12}}) {
    ImageF a(w, h, 1), b(w, h, 1);
    for (size_t i = 0; i < a.data.size(); ++i) {
      a.data[i] = u(rng);
      b.data[i] = std::clamp(a.data[i] + 0.4f * (u(rng) - 0.5f), 0.0f, 1.0f);
    }
    const long double want = ssim_brute_force(a, b);
    EXPECT_NEAR(ssim(a, b), double(want), 1e-12) << w << "x" << h;
    EXPECT_LT(want, 0.95L);
  }
}

TEST(Ssim, IdenticalImagesScoreOne) {
  std::mt19937 rng(5);
  for (const auto& s : {std::pair{40, 30}, std::pair{7, 25}, std::pair{3, 2}}) {
    ImageF a(s.first, s.second, 1);
    for (float& v : a.data) v = float(rng() % 101) / 100.0f;
    EXPECT_NEAR(ssim(a, a), 1.0, 1e-12) << s.first << "x" << s.second;
  }
}

TEST(Ssim, ConstantImagesFollowLuminanceTerm) {
  // Valid windows only (20×20) and the clamped fallback (5×5) give the same constant value.
  for (const int size : {20, 5}) {
    EXPECT_NEAR(ssim(ImageF(size, size, 1, 0.5f), ImageF(size, size, 1, 0.25f)),
                constant_pair_ssim(0.5, 0.25), 1e-12);
    EXPECT_NEAR(ssim(ImageF(size, size, 1, 1.0f), ImageF(size, size, 1, 0.0f)),
                constant_pair_ssim(1.0, 0.0), 1e-12);
  }
}

TEST(Ssim, FromMomentsHandValue) {
  // μa = 0.5, μb = 0.4, σa² = 0.04, σb² = 0.09, σab = 0.03:
  // (2·0.2 + C1)(0.06 + C2) / ((0.25 + 0.16 + C1)(0.13 + C2)).
  const double c1 = 1e-4, c2 = 9e-4;
  EXPECT_NEAR(ssim_from_moments(0.5, 0.4, 0.04, 0.09, 0.03),
              (0.4 + c1) * (0.06 + c2) / ((0.41 + c1) * (0.13 + c2)), 1e-15);
}

TEST(Ssim, OffsetEdgeIsBelowOne) {
  ImageF a(32, 32, 1, 0.0f), b(32, 32, 1, 0.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 16; x < 32; ++x) a.at(x, y) = 1.0f;
  for (int y = 0; y < 32; ++y)
    for (int x = 18; x < 32; ++x) b.at(x, y) = 1.0f;
  const double s = ssim(a, b);
  EXPECT_LT(s, 1.0);
  EXPECT_GT(s, 0.0);
  EXPECT_DOUBLE_EQ(s, ssim(b, a));  // symmetric
}

TEST(ImageError, RmseAndPsnrByHand) {
  // Constant 0.5 vs 0.25: RMSE 0.25, PSNR = 20·log10(1/0.25) = 20·log10(4).
  const ImageF a(10, 10, 1, 0.5f), b(10, 10, 1, 0.25f);
  EXPECT_DOUBLE_EQ(rmse(a, b), 0.25);
  EXPECT_NEAR(psnr_from_rmse(rmse(a, b)), 20.0 * std::log10(4.0), 1e-12);
  // Two of four pixels differ by 1: MSE 0.5, PSNR = 10·log10(2).
  ImageF c(2, 2, 1, 0.0f), d(2, 2, 1, 0.0f);
  c.at(0, 0) = 1.0f;
  d.at(1, 1) = 1.0f;
  EXPECT_DOUBLE_EQ(rmse(c, d), std::sqrt(0.5));
  EXPECT_NEAR(psnr_from_rmse(rmse(c, d)), 10.0 * std::log10(2.0), 1e-12);
}

TEST(ImageError, IdenticalImagesHitThePsnrCap) {
  const ImageF a(4, 4, 1, 0.3f);
  EXPECT_EQ(rmse(a, a), 0.0);
  EXPECT_EQ(psnr_from_rmse(0.0), kPsnrCapDb);
  EXPECT_EQ(psnr_from_rmse(1e-6), kPsnrCapDb);  // 120 dB, capped
  EXPECT_NEAR(psnr_from_rmse(1e-3), 60.0, 1e-12);
}

TEST(Ssim, MismatchedSizesThrow) {
  EXPECT_THROW(ssim(ImageF(4, 4, 1), ImageF(4, 5, 1)), InputError);
  EXPECT_THROW(rmse(ImageF(4, 4, 1), ImageF(4, 5, 1)), InputError);
}

}  // namespace
}  // namespace shadowlab
