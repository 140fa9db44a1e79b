#include "metric/coverage.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace shadowlab {
namespace {

ImageD row(std::initializer_list<double> values) {
  ImageD img(int(values.size()), 1, 1);
  img.data.assign(values.begin(), values.end());
  return img;
}

TEST(Coverage, HandMadeCase) {
  // Reference dark region (< 0.1): pixels 0, 1, 2. The test is dark at 1 only (0.2 and 0.1
  // are not < 0.1) → dark = 1 − 2/3. Lit region (> 0.9): pixels 4, 5; the test is lit at 5 only
  // (0.9 is not > 0.9) → lit = 1 − 1/2. Pixel 3 (0.5) is in neither region.
  const ImageD br = row({0.0, 0.05, 0.09, 0.5, 0.95, 1.0});
  const ImageD bt = row({0.2, 0.0, 0.1, 0.0, 0.9, 1.0});
  EXPECT_NEAR(dark_coverage(bt, br), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(lit_coverage(bt, br), 0.5, 1e-15);
}

TEST(Coverage, ThresholdValuesAreInNoRegion) {
  // Exactly 0.1 is not dark and exactly 0.9 is not lit: both regions empty → 1.
  const ImageD br = row({0.1, 0.9, 0.5});
  const ImageD bt = row({1.0, 0.0, 0.5});
  EXPECT_EQ(dark_coverage(bt, br), 1.0);
  EXPECT_EQ(lit_coverage(bt, br), 1.0);
}

TEST(Coverage, IdenticalAndOppositeMasks) {
  ImageD a(20, 10, 1, 0.0), b(20, 10, 1, 1.0);
  for (int y = 0; y < 10; ++y)
    for (int x = 10; x < 20; ++x) a.at(x, y) = 1.0;
  EXPECT_EQ(dark_coverage(a, a), 1.0);
  EXPECT_EQ(lit_coverage(a, a), 1.0);
  // All-lit test against the half-dark reference: every dark pixel missed, every lit one kept.
  EXPECT_EQ(dark_coverage(b, a), 0.0);
  EXPECT_EQ(lit_coverage(b, a), 1.0);
}

TEST(Coverage, MismatchedSizesThrow) {
  EXPECT_THROW(dark_coverage(ImageD(3, 3, 1), ImageD(3, 4, 1)), InputError);
}

}  // namespace
}  // namespace shadowlab
