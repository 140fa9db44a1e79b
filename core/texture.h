#pragma once
// Texture files and the one alpha lookup shared by the rasterizer and the Embree reference
// (both passes must discard exactly the same fragments).
//
// Conventions: texture images follow Image<T> (origin top-left, row 0 = the first row stored in
// the file). OBJ texture coordinates have v pointing up, so uv (0, 0) is the bottom-left corner
// of the image and uv (1, 1) the top-right one. Lookups wrap (repeat) and take the nearest
// texel: texel column floor(frac(u) * W), texel row (from the bottom) floor(frac(v) * H).
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/math.h"

namespace shadowlab {

// An 8-bit texture as decoded by stb, always expanded to 4 interleaved channels (RGBA; a file
// without alpha gets alpha 255, a grey file gets R = G = B = grey).
struct Texture8 {
  int width = 0;
  int height = 0;
  int file_channels = 0;      // channels stored in the file: 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
  std::vector<uint8_t> rgba;  // interleaved RGBA, row-major, top row first

  bool file_has_alpha() const { return file_channels == 2 || file_channels == 4; }
  uint8_t at(int x, int y, int c) const {
    return rgba[(size_t(y) * size_t(width) + size_t(x)) * 4 + size_t(c)];
  }
};

// Loads a PNG/JPG/TGA/BMP (anything stb_image decodes; 16-bit files are reduced to 8 bits).
// Throws InputError(path, "cannot open: <strerror>") or InputError(path, "cannot decode ...").
Texture8 load_texture8(const std::string& path);
// Width and height of a PNG/JPEG from its header, without decoding; InputError when unreadable.
std::pair<int, int> image_file_size(const std::string& path);

// sRGB transfer functions on [0, 1] (IEC 61966-2-1 piecewise curve).
float srgb_to_linear(float srgb);
float linear_to_srgb(float linear);
// Linear value → 8-bit sRGB code: clamps to [0, 1] (NaN → 0) and rounds to nearest.
uint8_t linear_to_srgb8(float linear);
// Exact sRGB → linear for an 8-bit code (table lookup).
float srgb8_to_linear(uint8_t code);

// Planar 4-channel ImageF from an 8-bit texture: R, G, B converted sRGB → linear, alpha = A/255
// as stored (alpha is never gamma-decoded).
ImageF texture_to_linear_rgba(const Texture8& tex);

// t − floor(t) in [0, 1); non-finite t gives 0. Inline and libm-free (the alpha test runs per
// fragment): for |t| >= 2^23 every float is an integer, so the fraction is 0; below that,
// truncation corrected for negative non-integers is exactly floor(t).
inline float wrap01(float t) {
  if (!(std::fabs(t) < 8388608.0f)) return 0.0f;  // also NaN and ±inf
  const float tr = float(int(t));
  const float f = t - (tr > t ? tr - 1.0f : tr);
  return f < 1.0f ? f : 0.0f;  // t − floor(t) can round up to 1 for tiny negative t
}

// Alpha of an RGBA ImageF (channel 3) at texture coordinate uv: nearest texel, repeat wrap,
// v up (see the top of this file). Non-finite coordinates read texel (0, 0) of the wrap cell.
// The image must be a non-empty 4-channel one (validate_scene checks every alpha texture).
inline float sample_alpha(const ImageF& rgba, vec2 uv) {
  const int w = rgba.width, h = rgba.height;
  int x = int(wrap01(uv.x) * float(w));
  int row_from_bottom = int(wrap01(uv.y) * float(h));
  if (x >= w) x = w - 1;
  if (row_from_bottom >= h) row_from_bottom = h - 1;
  return rgba.data[(size_t(3) * size_t(h) + size_t(h - 1 - row_from_bottom)) * size_t(w) + size_t(x)];
}

// Linear RGB of an RGBA ImageF at texture coordinate uv: the texel sample_alpha reads.
inline vec3 sample_rgb(const ImageF& rgba, vec2 uv) {
  const int w = rgba.width, h = rgba.height;
  int x = int(wrap01(uv.x) * float(w));
  int row_from_bottom = int(wrap01(uv.y) * float(h));
  if (x >= w) x = w - 1;
  if (row_from_bottom >= h) row_from_bottom = h - 1;
  const size_t texel = size_t(h - 1 - row_from_bottom) * size_t(w) + size_t(x);
  const size_t plane = size_t(w) * size_t(h);
  return vec3(rgba.data[texel], rgba.data[plane + texel], rgba.data[2 * plane + texel]);
}

// Texture coordinate at barycentrics (b1, b2) of triangle `tri` (3 vertex indices) of a mesh
// with per-vertex `uvs`: (1 − b1 − b2)·uv0 + b1·uv1 + b2·uv2, in this order, the one
// interpolation of the rasterizer (perspective-correct barycentrics) and of Embree's filters
// (its hit u, v), so both read the same texel for the same surface point.
inline vec2 barycentric_uv(const vec2* uvs, const uint32_t* tri, float b1, float b2) {
  return (1.0f - b1 - b2) * uvs[tri[0]] + b1 * uvs[tri[1]] + b2 * uvs[tri[2]];
}

// The alpha test of both passes: a fragment survives iff alpha >= cutoff.
inline bool alpha_test_passes(float alpha, float cutoff) { return alpha >= cutoff; }

}  // namespace shadowlab
