#pragma once
// EXR and PNG I/O. Masks: one float32 channel "Y". Texel indices: one UINT channel "texel".
// PNG previews: 8-bit sRGB-encoded grey for people (not for measurement). Texture loading
// (PNG/JPG via stb) returns linear RGBA floats in [0,1] for alpha testing and slides.
// Every failure throws InputError naming the file and the reason.
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace shadowlab {

// Text attributes written into an EXR header (name → value; provenance, docs/provenance.md),
// readable with `exrheader`.
using ExrAttributes = std::vector<std::pair<std::string, std::string>>;

void write_exr_mask(const std::string& path, const ImageF& mask, const ExrAttributes& attributes = {});
ImageF read_exr_mask(const std::string& path);
void write_exr_texels(const std::string& path, const ImageU32& texels,
                      const ExrAttributes& attributes = {});
ImageU32 read_exr_texels(const std::string& path);
// Linear RGB EXR (float32 channels R, G, B) of a 3-channel image (shaded projector renders).
void write_exr_rgb(const std::string& path, const ImageF& rgb, const ExrAttributes& attributes = {});
// Width and height of an EXR from its header (the data window), without reading pixels.
std::pair<int, int> exr_image_size(const std::string& path);
// The text attributes of an EXR header, in header order (the write functions' `attributes`).
ExrAttributes read_exr_attributes(const std::string& path);
// Reads an EXR as linear RGB (3 channels): R, G, B if present (any pixel type, converted to
// float), else a grey Y channel copied to all three. Throws InputError naming the file.
ImageF read_exr_rgb(const std::string& path);
// 8-bit PNG of a one-channel image in [0,1] (clamped), sRGB-encoded.
void write_png_grey(const std::string& path, const ImageF& image);
// 8-bit PNG of an RGB image (3 channels, linear [0,1], sRGB-encoded on write).
void write_png_rgb(const std::string& path, const ImageF& image);
// Loads an 8-bit PNG/JPG/TGA/BMP texture as 4 channels (RGBA) in [0,1]; colour channels are
// converted from sRGB to linear, alpha stays as stored.
ImageF load_texture_rgba(const std::string& path);

}  // namespace shadowlab
