#pragma once
// A picture of where a test mask's penumbra is too wide or too narrow against a reference:
// the reference's 10 % and 90 % visibility contours over the two masks' difference.
#include "core/image.h"

namespace shadowlab {

// RGB (3 planes, linear [0, 1]) of the same size as the masks:
//   background  grey 0.35 + 0.5 × reference (the scene's shadows, dimmed);
//   red tint    the test is lighter than the reference by more than 0.1 (its penumbra reaches too
//               far into the umbra, or a shadow is missing);
//   blue tint   the test is darker by more than 0.1 (its penumbra reaches too far into the lit
//               side, or acne);
//   black       the reference's 10 % and 90 % contours, yellow (kTestContourRgb) the test's (a
//               pixel is on a level's contour when its 2×2 block spans the level:
//               metric/contour.h's rule, unblurred).
// The two masks must have the same size (one channel each).
ImageF contour_comparison(const ImageF& test, const ImageF& ref);

// The test's contour colour: saturated, so that it differs from every grey of the background
// (0.35 to 0.85, and white around the picture in a viewer) by at least 0.5 in one channel and
// from the red and blue tints in green; white would vanish on the lit grey.
constexpr float kTestContourRgb[3] = {1.0f, 0.85f, 0.0f};

}  // namespace shadowlab
