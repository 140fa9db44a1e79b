#pragma once
// Reusing image memory across calls: fresh multi-megabyte buffers cost a page fault per 4 KiB
// on first touch, which dominates a metric evaluation when it is repeated in a sweep.
#include "core/image.h"

namespace shadowlab {

// Makes `img` a w × h × c image, keeping its allocation when it is already large enough. The
// contents are unspecified afterwards: callers overwrite every value.
template <class T>
void reshape_image(Image<T>& img, int w, int h, int c = 1) {
  img.width = w;
  img.height = h;
  img.channels = c;
  img.data.resize(size_t(w) * size_t(h) * size_t(c));
}

}  // namespace shadowlab
