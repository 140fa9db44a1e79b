#pragma once
// NumPy arrays over shadowlab's images (docs/python.md "Views and copies"). A view shares the
// C++ buffer and keeps its owner (the Python object holding it) alive through the array's base;
// inputs are copied into shadowlab images after their dtype and shape are checked.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "core/gbuffer.h"
#include "core/image.h"

namespace shadowlab::python {

namespace py = pybind11;

// A height × width view of a row-major plane owned by `owner`.
template <class T>
py::array plane_view(py::object owner, const T* data, int width, int height) {
  return py::array_t<T>({py::ssize_t(height), py::ssize_t(width)},
                        {py::ssize_t(width) * py::ssize_t(sizeof(T)), py::ssize_t(sizeof(T))},
                        data, owner);
}

// A height × width × 3 float32 view of a GBuffer's per-pixel vec3 array.
inline py::array vec3_view(py::object owner, const std::vector<vec3>& v, const GBuffer& g) {
  static_assert(sizeof(vec3) == 3 * sizeof(float), "vec3 must be three packed floats");
  return py::array_t<float>({py::ssize_t(g.height), py::ssize_t(g.width), py::ssize_t(3)},
                            {py::ssize_t(g.width) * 12, py::ssize_t(12), py::ssize_t(4)},
                            reinterpret_cast<const float*>(v.data()), owner);
}

// A copy of a planar 3-channel image as height × width × 3 float32 (the image's channels are
// planes, NumPy's convention interleaves them).
inline py::array rgb_copy(const ImageF& img) {
  py::array_t<float> a({py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(3)});
  auto w = a.mutable_unchecked<3>();
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) w(y, x, c) = img.at(x, y, c);
  return a;
}

// A 2-D array of exactly dtype T (no conversion: a float64 mask would be rounded silently)
// copied into an image; InputError(where, reason) otherwise.
template <class T>
Image<T> image_from_array(const py::array& a, const std::string& where, const char* dtype) {
  if (!py::isinstance<py::array_t<T>>(a) || a.dtype().kind() != py::dtype::of<T>().kind() ||
      a.itemsize() != py::ssize_t(sizeof(T)))
    throw InputError(where, std::string("expected a ") + dtype + " array, got dtype " +
                                std::string(py::str(a.dtype())));
  if (a.ndim() != 2)
    throw InputError(where, "expected a 2-D array (height, width), got " +
                                std::to_string(a.ndim()) + " dimensions");
  const py::ssize_t h = a.shape(0), w = a.shape(1);
  if (h < 1 || w < 1 || h > kMaxImageSide || w > kMaxImageSide)
    throw InputError(where, "each side must lie in [1, " + std::to_string(kMaxImageSide) +
                                "], got " + std::to_string(h) + "x" + std::to_string(w));
  Image<T> img{int(w), int(h)};
  auto r = a.unchecked<T, 2>();
  for (py::ssize_t y = 0; y < h; ++y)
    for (py::ssize_t x = 0; x < w; ++x) img.at(int(x), int(y)) = r(y, x);
  return img;
}

inline ImageF mask_from_array(const py::array& a, const std::string& where) {
  return image_from_array<float>(a, where, "float32");
}
inline ImageU32 texels_from_array(const py::array& a, const std::string& where) {
  return image_from_array<uint32_t>(a, where, "uint32");
}

}  // namespace shadowlab::python
