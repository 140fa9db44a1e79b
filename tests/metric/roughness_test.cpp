#include "metric/roughness.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "metric/box_blur.h"

namespace shadowlab {
namespace {

// Small images have k = 1, so the blurred reference equals the reference.
TEST(Roughness, RobertsCrossOfTwoByTwoBlocks) {
  // g = √((a − d)² + (b − c)²) for the block [a b; c d].
  ImageF m(2, 2, 1, 0.0f);
  m.at(0, 0) = 1.0f;  // [1 0; 0 0] → 1
  EXPECT_DOUBLE_EQ(roberts_cross(m, 0, 0), 1.0);
  m.at(0, 1) = 1.0f;  // [1 0; 1 0] → √(1 + 1)
  EXPECT_DOUBLE_EQ(roberts_cross(m, 0, 0), std::sqrt(2.0));
  m.at(1, 1) = 1.0f;  // [1 0; 1 1] → √(0 + 1)
  EXPECT_DOUBLE_EQ(roberts_cross(m, 0, 0), 1.0);
  // Fractional differences, where a ≠ a²: [1 0; 0 0.5] → 0.5, [0 0.7; 0.3 0] → 0.4,
  // [0.3 0.4; 0 0] → √(0.09 + 0.16) = 0.5.
  ImageF f(2, 2, 1, 0.0f);
  f.at(0, 0) = 1.0f, f.at(1, 1) = 0.5f;
  EXPECT_DOUBLE_EQ(roberts_cross(f, 0, 0), 0.5);
  ImageF g(2, 2, 1, 0.0f);
  g.at(1, 0) = 0.7f, g.at(0, 1) = 0.3f;
  EXPECT_NEAR(roberts_cross(g, 0, 0), 0.4, 1e-7);
  ImageF h(2, 2, 1, 0.0f);
  h.at(0, 0) = 0.3f, h.at(1, 0) = 0.4f;
  EXPECT_NEAR(roberts_cross(h, 0, 0), 0.5, 1e-7);
}

// The 2 × 2 block must lie inside the image: its last top-left corner is (w − 2, h − 2).
TEST(RoughnessDeathTest, RobertsCrossOutsideTheImageIsACheckFailure) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const ImageF m(3, 2, 1, 0.0f);
  EXPECT_DEATH(roberts_cross(m, 2, 0), "CHECK");
  EXPECT_DEATH(roberts_cross(m, 0, 1), "CHECK");
  EXPECT_DEATH(roberts_cross(m, -1, 0), "CHECK");
  EXPECT_EQ(roberts_cross(m, 1, 0), 0.0);
}

TEST(Roughness, ScoreFormula) {
  EXPECT_DOUBLE_EQ(roughness_score(0.3, 0.1), 0.7 / 0.9);
  EXPECT_EQ(roughness_score(0.05, 0.1), 1.0);  // smoother than the reference: capped at 1
  EXPECT_EQ(roughness_score(1.2, 0.1), 0.0);   // negative ratio: clamped at 0
  // Special case 1 − R_RMS ≤ 0: 1 when T_RMS ≤ R_RMS, else 0.
  EXPECT_EQ(roughness_score(1.0, 1.0), 1.0);
  EXPECT_EQ(roughness_score(0.5, 1.2), 1.0);
  EXPECT_EQ(roughness_score(1.3, 1.2), 0.0);
  EXPECT_EQ(roughness_score(RobertsRegion{}), 1.0);  // empty region
}

TEST(Roughness, IsolatedDarkDotInLitRegion) {
  // 11×11 all lit, one dark test pixel at (5,5): the four cells whose 2×2 block contains it,
  // (4,4) (5,4) (4,5) (5,5), each have g² = 1; 10·10 = 100 lit cells.
  // T_RMS = √(4/100) = 0.2, R_RMS = 0 → acne = 0.8. No dark region → noise = 1.
  const ImageF ref(11, 11, 1, 1.0f);
  ImageF test = ref;
  test.at(5, 5) = 0.0f;
  const ImageD br = box_blur(ref, 1);
  EXPECT_NEAR(acne_score(test, ref, br), 0.8, 1e-15);
  EXPECT_EQ(noise_score(test, ref, br), 1.0);
  const RobertsSums s = roberts_sums(test, ref, br);
  EXPECT_EQ(s.lit.cells, 100u);
  EXPECT_EQ(s.lit.test_sum, 4.0);
  EXPECT_EQ(s.lit.ref_sum, 0.0);
  EXPECT_EQ(s.dark.cells, 0u);
}

TEST(Roughness, DotsNormalizedByReferenceRoughness) {
  // Reference: dark dot at (2,2); its cell (2,2) is dark (top-left pixel 0), so 99 lit cells,
  // three of which, (1,1) (2,1) (1,2), contain the dot (g² = 1 each): R_RMS = √(3/99).
  // Test: the same dot plus one at (7,7) whose four cells are all lit: T_RMS = √(7/99).
  // Dark region: cell (2,2) alone, g² = 1 in both → noise 1.
  ImageF ref(11, 11, 1, 1.0f);
  ref.at(2, 2) = 0.0f;
  ImageF test = ref;
  test.at(7, 7) = 0.0f;
  const ImageD br = box_blur(ref, 1);
  const double expected = (1.0 - std::sqrt(7.0 / 99.0)) / (1.0 - std::sqrt(3.0 / 99.0));
  EXPECT_NEAR(acne_score(test, ref, br), expected, 1e-15);
  EXPECT_EQ(noise_score(test, ref, br), 1.0);
  EXPECT_EQ(acne_score(ref, ref, br), 1.0);
}

TEST(Roughness, CheckerboardOfTwoByTwoBlocksInLitRegion) {
  // 9×9 test, 2×2 blocks alternating 1 and 0.5; reference all lit (64 lit cells, g = 0).
  // Cells with x, y both even or both odd see a = b = 0; cells with one odd coordinate straddle
  // one block border: a = ±0.5, b = ∓0.5, g² = 0.5. Half the cells → mean g² = 0.25,
  // T_RMS = 0.5, acne = 1 − 0.5 = 0.5.
  const ImageF ref(9, 9, 1, 1.0f);
  ImageF test(9, 9, 1, 1.0f);
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 9; ++x)
      if ((x / 2 + y / 2) % 2) test.at(x, y) = 0.5f;
  EXPECT_NEAR(acne_score(test, ref, box_blur(ref, 1)), 0.5, 1e-15);
}

TEST(Roughness, PixelCheckerboardIsInvisibleToRobertsCross) {
  // Diagonal neighbours of a one-pixel checkerboard are equal, so g = 0 everywhere: the
  // Roberts cross cannot see this pattern (coverage and contours do).
  const ImageF ref(8, 8, 1, 1.0f);
  ImageF test(8, 8, 1, 1.0f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      if ((x + y) % 2) test.at(x, y) = 0.0f;
  EXPECT_EQ(acne_score(test, ref, box_blur(ref, 1)), 1.0);
}

TEST(Roughness, ReferenceRougherThanOneUsesSpecialCase) {
  // Reference: vertical stripes 1, 0.25, 1, 0.25, … (8×4). Lit cells: x ∈ {0, 2, 4, 6},
  // y ∈ {0, 1, 2}; each has a = 0.75, b = −0.75, g² = 1.125 → R_RMS = √1.125 > 1.
  // Test stripes 1, 0: g² = 2, T_RMS = √2 > R_RMS → 0. Test stripes 1, 0.5: T_RMS = √0.5 → 1.
  auto stripes = [](float low) {
    ImageF m(8, 4, 1, 1.0f);
    for (int y = 0; y < 4; ++y)
      for (int x = 1; x < 8; x += 2) m.at(x, y) = low;
    return m;
  };
  const ImageF ref = stripes(0.25f);
  const ImageD br = box_blur(ref, 1);
  const RobertsSums s = roberts_sums(ref, ref, br);
  EXPECT_EQ(s.lit.cells, 12u);
  EXPECT_DOUBLE_EQ(s.lit.ref_sum, 12 * 1.125);
  EXPECT_EQ(acne_score(stripes(0.0f), ref, br), 0.0);
  EXPECT_EQ(acne_score(stripes(0.5f), ref, br), 1.0);
  EXPECT_EQ(acne_score(ref, ref, br), 1.0);
}

TEST(Roughness, DegenerateSizesHaveNoCells) {
  const ImageF line(7, 1, 1, 1.0f);
  EXPECT_EQ(acne_score(line, line, box_blur(line, 1)), 1.0);
  EXPECT_THROW(roberts_sums(ImageF(3, 3, 1), ImageF(3, 4, 1), ImageD(3, 4, 1)), InputError);
}

}  // namespace
}  // namespace shadowlab
