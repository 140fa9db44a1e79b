#include "metric/visible_difference.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace shadowlab {
namespace {

TEST(VisibleDifference, IdenticalImagesShowNothing) {
  ImageF a(32, 24, 1, 0.3f);
  for (size_t i = 0; i < a.data.size(); ++i) a.data[i] = float(i % 7) / 7.0f;
  const VisibleDifference d = visible_difference(a, a);
  EXPECT_EQ(d.plain, 0.0);
  EXPECT_EQ(d.masked, 0.0);
}

TEST(VisibleDifference, EmptyImagesShowNothing) {
  // No pixel, so no pixel differs: both fractions are 0, not 0/0.
  const ImageF empty(0, 0, 1, 0.0f);
  const VisibleDifference d = visible_difference(empty, empty);
  EXPECT_EQ(d.plain, 0.0);
  EXPECT_EQ(d.masked, 0.0);
}

TEST(VisibleDifference, SmoothBackgroundDoesNotMask) {
  // A flat reference has σ = 0 everywhere: no elevation, so an offset of 3/255 (> 2/255) is
  // visible at every pixel under both thresholds, and one of 1/255 at none.
  const ImageF ref(40, 30, 1, 0.5f);
  const ImageF big(40, 30, 1, 0.5f + 3.0f / 255.0f);
  const ImageF small(40, 30, 1, 0.5f + 1.0f / 255.0f);
  EXPECT_EQ(visible_difference(ref, big).plain, 1.0);
  EXPECT_EQ(visible_difference(ref, big).masked, 1.0);
  EXPECT_EQ(visible_difference(ref, small).plain, 0.0);
}

TEST(VisibleDifference, BusyPatternMasksTheSameError) {
  // A 0/1 checkerboard has σ ≈ 0.5 in every 7×7 window (24 vs 25 cells: σ² = 0.2496), so the
  // threshold rises to (2/255)·(0.4996/(2/255))^0.7 ≈ 0.144: an offset of 3/255 = 0.0118 hides
  // everywhere, while it is still over the plain 2/255 threshold everywhere.
  ImageF ref(40, 30, 1), test(40, 30, 1);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      ref.at(x, y) = float((x + y) % 2) * 0.9f + 0.05f;  // 0.05 / 0.95: room for the offset
      test.at(x, y) = ref.at(x, y) + 3.0f / 255.0f;
    }
  const VisibleDifference d = visible_difference(ref, test);
  EXPECT_EQ(d.plain, 1.0);
  EXPECT_EQ(d.masked, 0.0);
  // An error of 0.3 is above the elevated threshold (≈ 0.13 for σ = 0.45): visible again.
  for (float& v : test.data) v += 0.3f - 3.0f / 255.0f;
  EXPECT_EQ(visible_difference(ref, test).masked, 1.0);
}

TEST(VisibleDifference, SizeMismatchIsAnInputError) {
  EXPECT_THROW(visible_difference(ImageF(4, 4, 1), ImageF(4, 5, 1)), InputError);
  EXPECT_THROW(visible_difference(ImageF(4, 4, 3), ImageF(4, 4, 3)), InputError);
}

}  // namespace
}  // namespace shadowlab
