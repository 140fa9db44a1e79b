#include "metric/distance_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace shadowlab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Brute force: the minimum squared distance to any set pixel.
double brute_distance2(const ImageU8& m, int x, int y) {
  double best = kInf;
  for (int v = 0; v < m.height; ++v)
    for (int u = 0; u < m.width; ++u)
      if (m.at(u, v)) best = std::min(best, double((u - x) * (u - x) + (v - y) * (v - y)));
  return best;
}

TEST(DistanceTransform, MatchesBruteForceOnRandomMasks) {
  std::mt19937 rng(20240607);
  for (int trial = 0; trial < 60; ++trial) {
    const int w = 1 + int(rng() % 40);
    const int h = 1 + int(rng() % 40);
    const unsigned density = 1 + rng() % 200;  // per mille of set pixels
    ImageU8 m(w, h, 1);
    for (uint8_t& v : m.data) v = (rng() % 1000) < density ? 1 : 0;
    const ImageD d = squared_distance_transform(m);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        ASSERT_EQ(d.at(x, y), brute_distance2(m, x, y))
            << "trial " << trial << " " << w << "x" << h << " at " << x << "," << y;
  }
}

TEST(DistanceTransform, SinglePixelGivesSquaredEuclideanDistance) {
  ImageU8 m(9, 7, 1);
  m.at(2, 3) = 1;
  const ImageD d = squared_distance_transform(m);
  EXPECT_EQ(d.at(2, 3), 0.0);
  EXPECT_EQ(d.at(5, 7 - 1), 9.0 + 9.0);  // (3, 3) away
  EXPECT_EQ(d.at(8, 0), 36.0 + 9.0);     // (6, −3) away
}

TEST(DistanceTransform, EmptyMaskIsInfiniteEverywhere) {
  const ImageD d = squared_distance_transform(ImageU8(6, 5, 1));
  for (const double v : d.data) EXPECT_EQ(v, kInf);
}

TEST(DistanceTransform, OneDimensionalEnvelopeMatchesBruteForce) {
  // General sampled functions (not only 0/none): d[q] = min_p (q − p)² + f[p].
  std::mt19937 rng(77);
  EnvelopeScratch scratch;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + int(rng() % 50);
    const uint32_t range = trial % 3 == 0 ? 5 : 300;  // small range: many ties
    std::vector<int32_t> f(static_cast<size_t>(n)), d(static_cast<size_t>(n));
    for (int32_t& v : f) v = rng() % 4 == 0 ? kNoSite : int32_t(rng() % range);
    squared_distance_1d(f.data(), n, d.data(), scratch);
    for (int q = 0; q < n; ++q) {
      int32_t best = kNoSite;
      for (int p = 0; p < n; ++p)
        if (f[size_t(p)] != kNoSite) best = std::min(best, (q - p) * (q - p) + f[size_t(p)]);
      ASSERT_EQ(d[size_t(q)], best) << "trial " << trial << " q " << q;
    }
  }
}

TEST(DistanceTransform, SelectedBitsOnly) {
  // Bit 1 set at (0,0), bit 2 at (4,0): each bit has its own distance field.
  ImageU8 m(5, 1, 1);
  m.at(0, 0) = 1;
  m.at(4, 0) = 2;
  EXPECT_EQ(squared_distance_transform(m, 1).at(3, 0), 9.0);
  EXPECT_EQ(squared_distance_transform(m, 2).at(3, 0), 1.0);
  EXPECT_EQ(squared_distance_transform(m).at(1, 0), 1.0);
}

}  // namespace
}  // namespace shadowlab
