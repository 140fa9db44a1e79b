// The contour-comparison picture on ramps whose contours and differences are known by hand.
#include "metric/contour_image.h"

#include <gtest/gtest.h>

#include <algorithm>

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
        EXPECT_TRUE(r == 1.0f && g == 1.0f && b == 1.0f) << x;
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

}  // namespace
}  // namespace shadowlab
