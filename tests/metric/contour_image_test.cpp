// The contour-comparison picture on ramps whose contours and differences are known by hand.
#include "metric/contour_image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace shadowlab {
namespace {

// ref(x) = (x + ½)/100 across a 101 × 3 image: its 10 % and 90 % levels fall between columns 9–10
// and 89–90, so columns 9 and 89 are its contour pixels. The test is the same ramp moved 20
// columns right (0 before): its 10 % contour is column 29 (its 90 % one is off the image). It is
// darker than the reference by more than 0.1 from column 10 on ((x + ½)/100 for x < 20, 0.2
// after), never lighter. Swapping the two gives red where blue was.
TEST(ContourImage, RampShiftedRightIsDarkWithContoursWhereExpected) {
  const int w = 101, h = 3;
  ImageF ref(w, h, 1), test(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      ref.at(x, y) = (float(x) + 0.5f) / 100.0f;
      test.at(x, y) = std::max(0.0f, (float(x) - 20.0f + 0.5f) / 100.0f);
    }
  for (const bool swapped : {false, true}) {
    const ImageF img = swapped ? contour_comparison(ref, test) : contour_comparison(test, ref);
    ASSERT_EQ(img.channels, 3);
    for (int x = 0; x < w; ++x) {
      const float r = img.at(x, 1, 0), g = img.at(x, 1, 1), b = img.at(x, 1, 2);
      // The reference's contours: columns 9 and 89 (swapped: the moved ramp's, 29).
      const bool ref_line = swapped ? x == 29 : (x == 9 || x == 89);
      const bool test_line = swapped ? (x == 9 || x == 89) : x == 29;
      if (ref_line) {
        EXPECT_TRUE(r == 0.0f && g == 0.0f && b == 0.0f) << x;
      } else if (test_line) {
        EXPECT_TRUE(r == 1.0f && g == 0.85f && b == 0.0f) << x;  // yellow
      } else if (x >= 10) {
        // Darker test: blue; swapped (the test is the lighter one): red.
        EXPECT_EQ(swapped ? r : b, 1.0f) << x;
        EXPECT_LT(swapped ? b : r, 0.5f) << x;
      } else {
        EXPECT_EQ(r, g) << x;  // grey: within 0.1
        EXPECT_EQ(g, b) << x;
      }
    }
  }
}

// The test's contour stays visible on any background: its colour, read from the picture, differs
// from every grey g in [0, 1] (the dimmed scene is 0.35..0.85; a viewer's page is white) by at
// least 0.4 in some channel. White (1, 1, 1) is 0.15 from the lit background and 0 from a page.
TEST(ContourImage, TestContourDiffersFromEveryGrey) {
  const int w = 101, h = 3;
  ImageF ref(w, h, 1, 1.0f), test(w, h, 1);
  for (int x = 0; x < w; ++x)
    for (int y = 0; y < h; ++y) test.at(x, y) = (float(x) + 0.5f) / 100.0f;
  // The test ramp's 10 % contour is column 9; the reference (all lit) has none.
  const ImageF img = contour_comparison(test, ref);
  const float c[3] = {img.at(9, 1, 0), img.at(9, 1, 1), img.at(9, 1, 2)};
  for (int k = 0; k <= 100; ++k) {
    const float g = float(k) / 100.0f;
    const float d = std::max({std::fabs(c[0] - g), std::fabs(c[1] - g), std::fabs(c[2] - g)});
    EXPECT_GE(d, 0.4f) << "contour colour " << c[0] << "," << c[1] << "," << c[2] << " vs grey " << g;
  }
  // And from the lit background next to it (column 50, where the test is 0.5: a blue tint, so
  // take a lit pixel of an all-lit pair instead).
  const ImageF lit = contour_comparison(ref, ref);
  for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(lit.at(50, 1, ch), 0.85f);
}

}  // namespace
}  // namespace shadowlab
