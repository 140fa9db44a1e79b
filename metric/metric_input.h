#pragma once
// Input checks shared by the metric's entry points. Every failure throws
// InputError("metric", reason) naming the image and, for bad values, the first bad pixel.
#include <string>

#include "core/image.h"

namespace shadowlab {

// `mask` must be a non-empty 1-channel image no larger than kMaxImageSide per side, with every
// value in [0, 1] (NaN and ±inf are rejected). `name` ("test mask", ...) goes in the message.
void check_mask(const ImageF& mask, const std::string& name);

// Test and reference masks: each passes check_mask, and both have the same size.
void check_mask_pair(const ImageF& test, const ImageF& ref);

// A texel-index image must be 1-channel and width × height.
void check_texels(const ImageU32& texels, int width, int height);

}  // namespace shadowlab
