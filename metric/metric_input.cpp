#include "metric/metric_input.h"

#include <cstdio>

#include <fmt/format.h>

#include "core/error.h"

namespace shadowlab {
namespace {

std::string size_text(int w, int h, int c) {
  return std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(c);
}

}  // namespace

void check_mask(const ImageF& mask, const std::string& name) {
  if (mask.empty()) throw InputError("metric", name + " is empty");
  if (mask.channels != 1)
    throw InputError("metric", name + " must have 1 channel, got " + std::to_string(mask.channels));
  if (mask.width > kMaxImageSide || mask.height > kMaxImageSide)
    throw InputError(
        "metric", name + " is larger than " + std::to_string(kMaxImageSide) + " pixels per side");
  if (mask.data.size() != mask.pixel_count())
    throw InputError("metric", name + " holds " + std::to_string(mask.data.size()) +
                                   " values, expected " + std::to_string(mask.pixel_count()));
  // A branch-free scan first (the common, valid case); locate the culprit only on failure.
  // !(v >= 0 && v <= 1) is true for NaN, ±inf and out-of-range values alike.
  bool bad = false;
  for (const float v : mask.data) bad |= !(v >= 0.0f && v <= 1.0f);
  if (!bad) return;
  for (size_t i = 0; i < mask.data.size(); ++i) {
    const float v = mask.data[i];
    if (v >= 0.0f && v <= 1.0f) continue;
    throw InputError("metric", name + " has value " + fmt::format("{:.9g}", double(v)) + " at pixel (" +
                                   std::to_string(i % size_t(mask.width)) + ", " +
                                   std::to_string(i / size_t(mask.width)) +
                                   "); masks must lie in [0, 1]");
  }
}

void check_mask_pair(const ImageF& test, const ImageF& ref) {
  check_mask(test, "test mask");
  check_mask(ref, "reference mask");
  if (test.width != ref.width || test.height != ref.height)
    throw InputError("metric", "test mask is " + size_text(test.width, test.height, 1) +
                                   " but reference mask is " + size_text(ref.width, ref.height, 1));
}

void check_texels(const ImageU32& texels, int width, int height) {
  if (texels.channels != 1 || texels.width != width || texels.height != height ||
      texels.data.size() != texels.pixel_count())
    throw InputError("metric", "texel-index image is " +
                                   size_text(texels.width, texels.height, texels.channels) +
                                   ", expected " + size_text(width, height, 1));
}

}  // namespace shadowlab
