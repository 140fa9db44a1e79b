#include "metric/contour_image.h"

#include <array>

#include "core/error.h"
#include "metric/contour.h"

namespace shadowlab {
namespace {

ImageD to_double(const ImageF& m) {
  ImageD d(m.width, m.height, 1);
  for (size_t i = 0; i < m.pixel_count(); ++i) d.data[i] = double(m.data[i]);
  return d;
}

}  // namespace

ImageF contour_comparison(const ImageF& test, const ImageF& ref) {
  SL_CHECK(test.width == ref.width && test.height == ref.height);
  SL_CHECK(test.channels == 1 && ref.channels == 1);
  const std::array<double, 2> levels = {0.1, 0.9};
  const ImageU8 ref_c = contour_bits(to_double(ref), levels);
  const ImageU8 test_c = contour_bits(to_double(test), levels);
  ImageF out(ref.width, ref.height, 3);
  for (size_t i = 0; i < ref.pixel_count(); ++i) {
    const float r = ref.data[i], t = test.data[i];
    float rgb[3];
    const float grey = 0.35f + 0.5f * r;
    rgb[0] = rgb[1] = rgb[2] = grey;
    if (t > r + 0.1f) {  // too light
      rgb[0] = 1.0f;
      rgb[1] = rgb[2] = 0.5f * grey;
    } else if (t < r - 0.1f) {  // too dark
      rgb[2] = 1.0f;
      rgb[0] = rgb[1] = 0.5f * grey;
    }
    if (test_c.data[i])
      for (int c = 0; c < 3; ++c) rgb[c] = kTestContourRgb[c];
    if (ref_c.data[i]) rgb[0] = rgb[1] = rgb[2] = 0.0f;  // the reference's lines on top
    for (int c = 0; c < 3; ++c) out.data[size_t(c) * ref.pixel_count() + i] = rgb[c];
  }
  return out;
}

}  // namespace shadowlab
