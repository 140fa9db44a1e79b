#include "metric/contour.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "metric/box_blur.h"

namespace shadowlab {
namespace {

// Dark for x < edge, lit from column `edge` on.
ImageF vertical_edge(int w, int h, int edge) {
  ImageF m(w, h, 1, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = edge; x < w; ++x) m.at(x, y) = 1.0f;
  return m;
}

TEST(Contour, MaskOnHandMadeBlock) {
  // Both rows [0 0.5 1]. Level 0.5: x = 0 block {0, 0.5} and x = 1 block {0.5, 1} contain it;
  // the last column sees only {1}. Level 0.9: only x = 1. The bottom row uses its own values.
  ImageD b(3, 2, 1);
  for (int y = 0; y < 2; ++y) {
    b.at(0, y) = 0.0;
    b.at(1, y) = 0.5;
    b.at(2, y) = 1.0;
  }
  const ImageU8 c50 = contour_mask(b, 0.5);
  const ImageU8 c90 = contour_mask(b, 0.9);
  for (int y = 0; y < 2; ++y) {
    EXPECT_EQ(c50.at(0, y), 1);
    EXPECT_EQ(c50.at(1, y), 1);
    EXPECT_EQ(c50.at(2, y), 0);
    EXPECT_EQ(c90.at(0, y), 0);
    EXPECT_EQ(c90.at(1, y), 1);
    EXPECT_EQ(c90.at(2, y), 0);
  }
}

TEST(Contour, BlockSpansTwoRows) {
  // Columns all equal, rows [0, 0, 1, 1] from top to bottom: only the block of row 1 spans
  // rows 1 and 2 = {0, 1}, which contains 0.1, 0.5 and 0.9; rows 0 ({0, 0}), 2 ({1, 1}) and the
  // last row ({1}) contain none of them. A block reading one row only would find no contour.
  ImageD b(3, 4, 1, 0.0);
  for (int x = 0; x < 3; ++x) b.at(x, 2) = b.at(x, 3) = 1.0;
  const ImageU8 bits = contour_bits(b, kContourLevels);
  for (int x = 0; x < 3; ++x) {
    EXPECT_EQ(bits.at(x, 0), 0) << "x " << x;
    EXPECT_EQ(bits.at(x, 1), 0b111) << "x " << x;
    EXPECT_EQ(bits.at(x, 2), 0) << "x " << x;
    EXPECT_EQ(bits.at(x, 3), 0) << "x " << x;
  }
  // Corner block: a single 1 at (1, 1) of a 3×3 zero image is in the blocks with top-left
  // (0, 0), (1, 0), (0, 1) and (1, 1), and in no other.
  ImageD c(3, 3, 1, 0.0);
  c.at(1, 1) = 1.0;
  const ImageU8 m = contour_mask(c, 0.5);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(m.at(x, y), (x <= 1 && y <= 1) ? 1 : 0) << x << "," << y;
}

// A test contour without a pixel at the reference's level is infinitely far (contour.h).
TEST(Contour, NoTestContourIsInfinitelyFar) {
  ImageU8 ref(16, 8, 1, 0), none(16, 8, 1, 0);
  ref.at(5, 3) = 0xFF;
  EXPECT_EQ(contour_distance_rms(none, ref), std::numeric_limits<double>::infinity());
  none.at(9, 3) = 0x01;  // a pixel of another level only
  EXPECT_EQ(contour_distance_rms(none, ref, 0x02), std::numeric_limits<double>::infinity());
  EXPECT_EQ(contour_distance_rms(none, ref, 0x01), 4.0);
}

TEST(Contour, ShiftedHorizontalEdgeGivesShiftAsRmsDistance) {
  // The vertical counterpart of ShiftedVerticalEdgeGivesShiftAsRmsDistance: a horizontal edge
  // moved by d rows puts every reference contour pixel exactly |d| from the test contour.
  const int w = 192, h = 256;
  ASSERT_EQ(blur_kernel_size(w, h), 3);
  auto horizontal_edge = [&](int edge) {
    ImageF m(w, h, 1, 0.0f);
    for (int y = edge; y < h; ++y)
      for (int x = 0; x < w; ++x) m.at(x, y) = 1.0f;
    return m;
  };
  const ImageD br = box_blur(horizontal_edge(100), 3);
  for (const int d : {1, 4, -6}) {
    const ImageD bt = box_blur(horizontal_edge(100 + d), 3);
    for (const double level : kContourLevels)
      EXPECT_NEAR(contour_distance_rms(contour_mask(bt, level), contour_mask(br, level)),
                  std::abs(d), 1e-12)
          << "shift " << d << " level " << level;
  }
}

TEST(Contour, AllValuesEqualToLevelAreContour) {
  // The paper's corner case: a flat block exactly at the level is marked.
  const ImageU8 c = contour_mask(ImageD(4, 3, 1, 0.5), 0.5);
  for (const uint8_t v : c.data) EXPECT_EQ(v, 1);
  const ImageU8 none = contour_mask(ImageD(4, 3, 1, 0.5), 0.9);
  for (const uint8_t v : none.data) EXPECT_EQ(v, 0);
}

TEST(Contour, DistanceRmsOfPoints) {
  // One reference point (2,2), test point (5,6): distance 5.
  ImageU8 t(10, 10, 1), r(10, 10, 1);
  t.at(5, 6) = 1;
  r.at(2, 2) = 1;
  EXPECT_DOUBLE_EQ(contour_distance_rms(t, r), 5.0);
  // A second reference point (5,9), 3 below the test point: RMS of 5 and 3 = √17.
  r.at(5, 9) = 1;
  EXPECT_DOUBLE_EQ(contour_distance_rms(t, r), std::sqrt(17.0));
}

TEST(Contour, ShiftedVerticalEdgeGivesShiftAsRmsDistance) {
  // 256×192 → k = 3. A blurred step is a ramp 0, 1/3, 2/3, 1 across the edge, so at each level
  // the contour is one full column that moves with the edge: every reference contour pixel is
  // exactly d from the test contour (same row), D_RMS = d, CM = 1 − d/(0.2·√(256·192)).
  const int w = 256, h = 192;
  ASSERT_EQ(blur_kernel_size(w, h), 3);
  const double d_max = 0.2 * std::sqrt(256.0 * 192.0);
  const ImageD br = box_blur(vertical_edge(w, h, 100), 3);
  for (const int d : {0, 1, 3, 10, -7}) {
    const ImageD bt = box_blur(vertical_edge(w, h, 100 + d), 3);
    for (const double level : kContourLevels) {
      EXPECT_NEAR(contour_distance_rms(contour_mask(bt, level), contour_mask(br, level)),
                  std::abs(d), 1e-12)
          << "shift " << d << " level " << level;
      EXPECT_NEAR(contour_score(bt, br, level), 1.0 - std::abs(d) / d_max, 1e-12)
          << "shift " << d << " level " << level;
    }
  }
}

TEST(Contour, ShiftedEdgeAtReferenceResolution) {
  // 1024×768, k = 11: the same argument; D_MAX = 0.2·√(1024·768).
  const int w = 1024, h = 768;
  const int k = blur_kernel_size(w, h);
  const ImageD br = box_blur(vertical_edge(w, h, 500), k);
  const ImageD bt = box_blur(vertical_edge(w, h, 504), k);
  EXPECT_NEAR(contour_score(bt, br, 0.5), 1.0 - 4.0 / (0.2 * std::sqrt(1024.0 * 768.0)), 1e-12);
}

TEST(Contour, OnlyOneContourScoresZeroNeitherScoresOne) {
  const int w = 40, h = 30;
  const ImageD edge = box_blur(vertical_edge(w, h, 20), 1);
  const ImageD lit = box_blur(ImageF(w, h, 1, 1.0f), 1);
  for (const double level : kContourLevels) {
    EXPECT_EQ(contour_score(lit, edge, level), 0.0);
    EXPECT_EQ(contour_score(edge, lit, level), 0.0);
    EXPECT_EQ(contour_score(lit, lit, level), 1.0);
  }
}

TEST(Contour, FarContourClampsToZero) {
  // 100×4: D_MAX = 0.2·√400 = 4; edges 10 columns apart → 1 − 10/4 < 0 → 0.
  const ImageD br = box_blur(vertical_edge(100, 4, 30), 1);
  const ImageD bt = box_blur(vertical_edge(100, 4, 40), 1);
  EXPECT_EQ(contour_score(bt, br, 0.5), 0.0);
}

TEST(Contour, BitsCarryOneLevelEach) {
  // Row [0 0.5 1] again: bit 0 (level 0.1) at x = 0, bit 1 (0.5) at x = 0 and 1, bit 2 (0.9)
  // at x = 1.
  ImageD b(3, 1, 1);
  b.at(0, 0) = 0.0;
  b.at(1, 0) = 0.5;
  b.at(2, 0) = 1.0;
  const ImageU8 bits = contour_bits(b, kContourLevels);
  EXPECT_EQ(bits.at(0, 0), 0b011);
  EXPECT_EQ(bits.at(1, 0), 0b110);
  EXPECT_EQ(bits.at(2, 0), 0);
}

TEST(Contour, ThreeLevelScoresMatchSingleLevelScores) {
  // Two offset soft discs: the shared-pass scores equal the one-level ones exactly.
  auto disc = [](double cx, double radius) {
    ImageF m(120, 90, 1);
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 120; ++x) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - 45.0);
        m.at(x, y) = float(std::clamp((d - radius) / 5.0 + 0.5, 0.0, 1.0));
      }
    return m;
  };
  const int k = blur_kernel_size(120, 90);
  const ImageD bt = box_blur(disc(58.0, 20.0), k);
  const ImageD br = box_blur(disc(62.0, 24.0), k);
  const auto all = contour_scores(bt, br);
  for (size_t l = 0; l < 3; ++l) {
    EXPECT_EQ(all[l], contour_score(bt, br, kContourLevels[l])) << "level " << l;
    EXPECT_LT(all[l], 1.0);
    EXPECT_GT(all[l], 0.0);
  }
}

TEST(Contour, MismatchedSizesThrow) {
  EXPECT_THROW(contour_score(ImageD(4, 4, 1), ImageD(5, 4, 1), 0.5), InputError);
}

TEST(ContourDeathTest, MoreLevelsThanBitsIsAProgrammerError) {
  // One bit per level in a byte: a ninth level has no bit.
  const ImageD b(3, 1, 1);
  const double nine[9] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};
  EXPECT_DEATH(contour_bits(b, std::span<const double>(nine, 9)), "CHECK");
  EXPECT_EQ(contour_bits(b, std::span<const double>(nine, 8)).width, 3);  // eight fit
}

}  // namespace
}  // namespace shadowlab
