#include "core/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVersion.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>
// The stb implementation lives in libstb.so (linked through PkgConfig::STB): declarations only.
#include <stb_image_write.h>

#include "core/error.h"
#include "core/input_file.h"
#include "core/output_file.h"
#include "core/run_inputs.h"
#include "core/texture.h"

namespace shadowlab {
namespace {

const char* pixel_type_name(Imf::PixelType t) {
  switch (t) {
    case Imf::UINT:
      return "UINT";
    case Imf::HALF:
      return "HALF";
    case Imf::FLOAT:
      return "FLOAT";
    default:
      return "unknown";
  }
}

// Fails with "cannot open: <strerror>", or for a path that is not a regular file of at most
// kImageFileLimit, before OpenEXR opens it (which would wait on a FIFO, and word a directory
// as a file that is not an EXR).
// The path is noted as an input of the run (core/run_inputs.h).
void require_readable(const std::string& path) {
  note_input(path);
  check_input_file(path, kImageFileLimit);
}

// Writes one channel `name` of type `type` from a width × height plane of T.
void add_attributes(Imf::Header& header, const ExrAttributes& attributes) {
  for (const auto& [name, value] : attributes) header.insert(name, Imf::StringAttribute(value));
}

template <class T>
void write_exr_channel(const std::string& path, const Image<T>& img, const char* name,
                       Imf::PixelType type, const ExrAttributes& attributes) {
  SL_CHECK_EQ(img.channels, 1);
  SL_CHECK_EQ(img.data.size(), img.pixel_count());
  if (img.empty())
    throw InputError(path, "cannot write an empty " + std::to_string(img.width) + "x" +
                               std::to_string(img.height) + " image");
  try {
    Imf::Header header(img.width, img.height);
    header.compression() = Imf::ZIP_COMPRESSION;  // lossless: round trips are bit-exact
    header.channels().insert(name, Imf::Channel(type));
    add_attributes(header, attributes);
    OutputFile out(path);  // a failed write leaves no truncated file under `path`
    {
      Imf::OutputFile file(out.temp_path().c_str(), header);
      Imf::FrameBuffer fb;
      fb.insert(name, Imf::Slice(type, reinterpret_cast<char*>(const_cast<T*>(img.data.data())),
                                 sizeof(T), sizeof(T) * size_t(img.width)));
      file.setFrameBuffer(fb);
      file.writePixels(img.height);
    }
    out.commit();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot write EXR: ") + e.what());
  }
}

// shadowlab's images start at pixel (0, 0) and cover the whole display window. An EXR whose
// data window starts elsewhere (a crop, an overscan) would be compared as if it did not.
void require_whole_window(const std::string& path, const Imf::Header& header) {
  const Imath::Box2i dw = header.dataWindow(), disp = header.displayWindow();
  if (dw.min.x != 0 || dw.min.y != 0 || dw != disp)
    throw InputError(path, "data window (" + std::to_string(dw.min.x) + "," + std::to_string(dw.min.y) +
                               ")-(" + std::to_string(dw.max.x) + "," + std::to_string(dw.max.y) +
                               ") is not the whole image from (0,0) (display window (" +
                               std::to_string(disp.min.x) + "," + std::to_string(disp.min.y) + ")-(" +
                               std::to_string(disp.max.x) + "," + std::to_string(disp.max.y) +
                               ")): crop or re-save it");
}

// No codec OpenEXR offers packs pixel data tighter than about 1000:1 (zlib's limit is 1032:1;
// RLE, PIZ and the lossy ones far less), so a header that declares more than 2048 bytes of
// pixels per byte of file is truncated or corrupt. Checked before anything is allocated: a
// 300-byte file declaring 16384² pixels used to cost a 1 GB image and seconds of decoding.
void require_plausible_size(const std::string& path, const Imf::Header& header, int channels,
                            int bytes_per_value) {
  const Imath::Box2i dw = header.dataWindow();
  // In 64 bits: a window's extent overflows int for hostile headers.
  const long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
  const long double declared = (long double)w * (long double)h * channels * bytes_per_value;
  std::error_code ec;
  const auto file_bytes = std::filesystem::file_size(path, ec);
  if (!ec && declared > (long double)file_bytes * 2048.0L)
    throw InputError(path, "declares " + std::to_string(w) + "x" + std::to_string(h) +
                               " pixels but holds only " + std::to_string(file_bytes) +
                               " bytes: truncated or corrupt");
}

// The header alone, read without opening the file for pixels (which would size and read its
// chunk offset tables from the declared window first): single-part scanline or tiled images
// only. Throws InputError naming the file.
Imf::Header peek_exr_header(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  char head[8] = {};
  if (!f.read(head, 8) || !Imf::isImfMagic(head)) throw InputError(path, "is not an EXR file");
  int version = 0;
  std::memcpy(&version, head + 4, 4);  // little-endian in the file and on x86-64
  if (Imf::isMultiPart(version) || Imf::isNonImage(version))
    throw InputError(path, "multi-part and deep EXR files are not supported");
  // Walk the attribute list (name, type, 32-bit size, value; an empty name ends it) before
  // OpenEXR reads it: it allocates each value at its declared size, so a size beyond the file
  // would cost gigabytes before failing.
  std::error_code ec;
  const uint64_t file_bytes = std::filesystem::file_size(path, ec);
  uint64_t pos = 8;
  for (int attribute = 0;; ++attribute) {
    std::string name, type;
    std::getline(f, name, '\0');
    if (!f) throw InputError(path, "EXR header ends early");
    if (name.empty()) break;
    std::getline(f, type, '\0');
    int32_t size = 0;
    if (!f || !f.read(reinterpret_cast<char*>(&size), 4)) throw InputError(path, "EXR header ends early");
    pos += name.size() + type.size() + 2 + 4;
    const uint64_t remaining = file_bytes - std::min(pos, file_bytes);
    if (size < 0 || uint64_t(size) > remaining || attribute > 10000)
      throw InputError(path, "EXR header attribute '" + name.substr(0, 32) + "' declares " +
                                 std::to_string(size) + " bytes, more than the file holds");
    if (type == "chlist") {
      // OpenEXR reads a channel list entry by entry (name, 16 bytes) up to an empty name,
      // whatever its declared size says: walk it the same way.
      for (;;) {
        std::string channel;
        std::getline(f, channel, '\0');
        if (!f) throw InputError(path, "EXR channel list ends early");
        pos += channel.size() + 1;
        if (channel.empty()) break;
        pos += 16;
        f.seekg(std::streamoff(pos));
      }
      continue;
    }
    if (type == "preview") {
      // Width and height, then width × height RGBA bytes, allocated at their declared size.
      uint32_t wh[2] = {0, 0};
      if (!f.read(reinterpret_cast<char*>(wh), 8)) throw InputError(path, "EXR preview ends early");
      if (uint64_t(wh[0]) * wh[1] * 4 > remaining)
        throw InputError(path, "EXR preview image declares " + std::to_string(wh[0]) + "x" +
                                   std::to_string(wh[1]) + " pixels, more than the file holds");
    }
    pos += uint64_t(size);
    f.seekg(std::streamoff(pos));
  }
  Imf::StdIFStream is(path.c_str());
  is.seekg(8);
  Imf::Header header;
  header.readFrom(is, version);
  return header;
}

// Reads channel `name`, which must exist and have exactly type `type`.
// Every check that needs only the header, made before OpenEXR opens the file for pixels (which
// sizes its chunk tables from the declared window): the window starts at (0, 0) and covers the
// image, its size is within kMaxImageSide, and the file can hold its pixels.
// bytes_per_value: the smallest the caller accepts (2 when half is allowed).
void check_exr_header(const std::string& path, int bytes_per_value) {
  const Imf::Header header = peek_exr_header(path);
  require_whole_window(path, header);
  const Imath::Box2i dw = header.dataWindow();
  const long long w = (long long)dw.max.x - dw.min.x + 1;
  const long long h = (long long)dw.max.y - dw.min.y + 1;
  if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
    throw InputError(path, "image size " + std::to_string(w) + "x" + std::to_string(h) +
                               " is outside [1, " + std::to_string(kMaxImageSide) + "]");
  const Imf::ChannelList& chans = header.channels();
  const int channels = chans.findChannel("R") && chans.findChannel("G") && chans.findChannel("B") ? 3 : 1;
  require_plausible_size(path, header, channels, bytes_per_value);
}

template <class T>
Image<T> read_exr_channel(const std::string& path, const char* name, Imf::PixelType type) {
  require_readable(path);
  try {
    check_exr_header(path, int(sizeof(T)));
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imf::Channel* ch = header.channels().findChannel(name);
    if (!ch) {
      std::string present;
      for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
        present += std::string(present.empty() ? "" : ", ") + it.name();
      throw InputError(path, std::string("no channel '") + name +
                                 "' (channels: " + (present.empty() ? "none" : present) + ")");
    }
    if (ch->type != type)
      throw InputError(path, std::string("channel '") + name + "' has type " +
                                 pixel_type_name(ch->type) + ", expected " + pixel_type_name(type));
    if (ch->xSampling != 1 || ch->ySampling != 1)
      throw InputError(path, std::string("channel '") + name + "' is subsampled");
    const Imath::Box2i dw = header.dataWindow();
    const long long w = (long long)dw.max.x - dw.min.x + 1;
    const long long h = (long long)dw.max.y - dw.min.y + 1;
    Image<T> img(int(w), int(h), 1);
    Imf::FrameBuffer fb;
    // Slice::Make offsets the base pointer by the data window origin without overflow.
    fb.insert(name, Imf::Slice::Make(type, img.data.data(), dw, sizeof(T), sizeof(T) * size_t(w)));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot read EXR: ") + e.what());
  }
}

// Writes a PNG through stb's in-memory encoder so file errors can be reported with strerror.
void write_png(const std::string& path, int w, int h, int comp, const std::vector<uint8_t>& px) {
  if (w < 1 || h < 1)
    throw InputError(
        path, "cannot write an empty " + std::to_string(w) + "x" + std::to_string(h) + " image");
  std::vector<unsigned char> encoded;
  auto sink = [](void* ctx, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(ctx);
    const auto* bytes = static_cast<const unsigned char*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(sink, &encoded, w, h, comp, px.data(), w * comp))
    throw InputError(path, "PNG encoding failed");
  write_text_file(path, std::string(encoded.begin(), encoded.end()));
}

}  // namespace

void write_exr_mask(const std::string& path, const ImageF& mask, const ExrAttributes& attributes) {
  write_exr_channel(path, mask, "Y", Imf::FLOAT, attributes);
}

ImageF read_exr_mask(const std::string& path) {
  return read_exr_channel<float>(path, "Y", Imf::FLOAT);
}

void write_exr_texels(const std::string& path, const ImageU32& texels,
                      const ExrAttributes& attributes) {
  write_exr_channel(path, texels, "texel", Imf::UINT, attributes);
}

ImageU32 read_exr_texels(const std::string& path) {
  return read_exr_channel<uint32_t>(path, "texel", Imf::UINT);
}

void write_exr_rgb(const std::string& path, const ImageF& rgb, const ExrAttributes& attributes) {
  SL_CHECK_EQ(rgb.channels, 3);
  SL_CHECK_EQ(rgb.data.size(), rgb.pixel_count() * 3);
  if (rgb.empty())
    throw InputError(path, "cannot write an empty " + std::to_string(rgb.width) + "x" +
                               std::to_string(rgb.height) + " image");
  try {
    Imf::Header header(rgb.width, rgb.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    add_attributes(header, attributes);
    add_attributes(header, attributes);
    const char* names[3] = {"R", "G", "B"};
    Imf::FrameBuffer fb;
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT,
                                     reinterpret_cast<char*>(const_cast<float*>(rgb.plane(c))),
                                     sizeof(float), sizeof(float) * size_t(rgb.width)));
    }
    OutputFile out(path);
    {
      Imf::OutputFile file(out.temp_path().c_str(), header);
      file.setFrameBuffer(fb);
      file.writePixels(rgb.height);
    }
    out.commit();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot write EXR: ") + e.what());
  }
}

ImageF read_exr_rgb(const std::string& path) {
  require_readable(path);
  try {
    check_exr_header(path, 2);  // half is the smallest pixel type
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imf::ChannelList& chans = header.channels();
    const bool rgb = chans.findChannel("R") && chans.findChannel("G") && chans.findChannel("B");
    if (!rgb && !chans.findChannel("Y"))
      throw InputError(path, "has neither R, G, B nor Y channels");
    const Imath::Box2i dw = header.dataWindow();
    const long long w = (long long)dw.max.x - dw.min.x + 1;
    const long long h = (long long)dw.max.y - dw.min.y + 1;
    ImageF img(int(w), int(h), 3);
    Imf::FrameBuffer fb;
    // OpenEXR converts HALF/UINT channels to the FLOAT slices on read.
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < (rgb ? 3 : 1); ++c)
      fb.insert(rgb ? names[c] : "Y",
                Imf::Slice::Make(Imf::FLOAT, img.plane(c), dw, sizeof(float), sizeof(float) * size_t(w)));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    if (!rgb)
      for (int c = 1; c < 3; ++c) std::copy(img.plane(0), img.plane(0) + img.pixel_count(), img.plane(c));
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot read EXR: ") + e.what());
  }
}

void write_png_grey(const std::string& path, const ImageF& image) {
  SL_CHECK_EQ(image.channels, 1);
  std::vector<uint8_t> px(image.pixel_count());
  for (size_t i = 0; i < px.size(); ++i) px[i] = linear_to_srgb8(image.data[i]);
  write_png(path, image.width, image.height, 1, px);
}

void write_png_rgb(const std::string& path, const ImageF& image) {
  SL_CHECK_EQ(image.channels, 3);
  // Planar → interleaved RGB.
  std::vector<uint8_t> px(image.pixel_count() * 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        px[(size_t(y) * size_t(image.width) + size_t(x)) * 3 + size_t(c)] =
            linear_to_srgb8(image.at(x, y, c));
  write_png(path, image.width, image.height, 3, px);
}

std::pair<int, int> exr_image_size(const std::string& path) {
  require_readable(path);
  try {
    const Imath::Box2i dw = peek_exr_header(path).dataWindow();
    return {int(std::min<long long>((long long)dw.max.x - dw.min.x + 1, INT_MAX)),
            int(std::min<long long>((long long)dw.max.y - dw.min.y + 1, INT_MAX))};
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot read EXR: ") + e.what());
  }
}

ExrAttributes read_exr_attributes(const std::string& path) {
  require_readable(path);
  try {
    const Imf::Header header = peek_exr_header(path);
    ExrAttributes out;
    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* a = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        out.emplace_back(it.name(), a->value());
    return out;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("cannot read EXR: ") + e.what());
  }
}

ImageF load_texture_rgba(const std::string& path) {
  return texture_to_linear_rgba(load_texture8(path));
}

}  // namespace shadowlab
