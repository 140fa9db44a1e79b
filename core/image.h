#pragma once
// Image<T>: row-major, planar channels. Origin top-left, x right, y down; pixel (x, y) has its
// centre at (x + 0.5, y + 0.5). Channel c of pixel (x, y) is data[(c * height + y) * width + x].
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/error.h"

namespace shadowlab {

// Largest image side any module accepts; larger sizes are rejected as bad input (they would
// only come from a typo and would allocate without bound).
constexpr int kMaxImageSide = 16384;

template <class T>
struct Image {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<T> data;

  Image() = default;
  Image(int w, int h, int c = 1, T fill = T{})
      : width(w), height(h), channels(c), data(size_t(w) * size_t(h) * size_t(c), fill) {
    SL_CHECK(w >= 0 && h >= 0 && c >= 1);
  }

  size_t pixel_count() const { return size_t(width) * size_t(height); }
  bool empty() const { return width == 0 || height == 0; }
  size_t index(int x, int y, int c = 0) const {
    return (size_t(c) * size_t(height) + size_t(y)) * size_t(width) + size_t(x);
  }
  T& at(int x, int y, int c = 0) { return data[index(x, y, c)]; }
  const T& at(int x, int y, int c = 0) const { return data[index(x, y, c)]; }
  // Pointer to the first element of channel c (a width × height plane).
  T* plane(int c) { return data.data() + size_t(c) * pixel_count(); }
  const T* plane(int c) const { return data.data() + size_t(c) * pixel_count(); }
};

using ImageF = Image<float>;
using ImageU32 = Image<uint32_t>;

// Sizes img to w × h with one channel, keeping existing storage and values (for writers that
// set every pixel: no clearing, and no fresh pages in timing loops).
template <class T>
void shape_single_channel(Image<T>& img, int w, int h) {
  img.width = w;
  img.height = h;
  img.channels = 1;
  img.data.resize(size_t(w) * size_t(h));
}

// Texel index meaning "no shadow-map texel here" (no geometry, or facing away from the light).
constexpr uint32_t kNoTexel = 0xFFFFFFFFu;

}  // namespace shadowlab
