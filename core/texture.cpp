#include "core/texture.h"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

// The stb implementation lives in libstb.so (linked through PkgConfig::STB): declarations only.
#include <stb_image.h>

#include "core/error.h"
#include "core/input_file.h"
#include "core/run_inputs.h"

namespace shadowlab {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

std::array<float, 256> make_srgb_table() {
  std::array<float, 256> t{};
  for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_to_linear(float(i) / 255.0f);
  return t;
}

}  // namespace

std::pair<int, int> image_file_size(const std::string& path) {
  note_input(path);
  InputFile checked(path, kTextureFileLimit);
  FilePtr file(::fdopen(checked.fd(), "rb"));
  if (!file) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  checked.release();  // closed with `file`
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_file(file.get(), &w, &h, &comp))
    throw InputError(path, std::string("cannot decode image: ") + stbi_failure_reason());
  return {w, h};
}

Texture8 load_texture8(const std::string& path) {
  note_input(path);
  const std::vector<unsigned char> bytes = read_input_bytes(path, kTextureFileLimit);
  const int size = int(bytes.size());  // kTextureFileLimit is below INT_MAX
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes.data(), size, &w, &h, &comp))
    throw InputError(path, std::string("cannot decode image: ") + stbi_failure_reason());
  if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
    throw InputError(path, "image size " + std::to_string(w) + "x" + std::to_string(h) +
                               " is outside [1, " + std::to_string(kMaxImageSide) + "]");
  int lw = 0, lh = 0, lcomp = 0;
  stbi_uc* pixels = stbi_load_from_memory(bytes.data(), size, &lw, &lh, &lcomp, 4);
  if (!pixels) throw InputError(path, std::string("cannot decode image: ") + stbi_failure_reason());
  Texture8 tex;
  tex.width = lw;
  tex.height = lh;
  tex.file_channels = lcomp;
  tex.rgba.assign(pixels, pixels + size_t(lw) * size_t(lh) * 4);
  stbi_image_free(pixels);
  return tex;
}

float srgb_to_linear(float s) {
  return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float l) {
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

uint8_t linear_to_srgb8(float l) {
  if (!(l > 0.0f)) return 0;  // also NaN
  if (l >= 1.0f) return 255;
  return uint8_t(std::lround(linear_to_srgb(l) * 255.0f));
}

float srgb8_to_linear(uint8_t code) {
  static const std::array<float, 256> table = make_srgb_table();
  return table[code];
}

ImageF texture_to_linear_rgba(const Texture8& tex) {
  ImageF img(tex.width, tex.height, 4);
  for (int y = 0; y < tex.height; ++y)
    for (int x = 0; x < tex.width; ++x) {
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = srgb8_to_linear(tex.at(x, y, c));
      img.at(x, y, 3) = float(tex.at(x, y, 3)) / 255.0f;
    }
  return img;
}


}  // namespace shadowlab
