#include "core/image_io.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>  // stb is a private dependency of core: full path
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/texture.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

// Expects fn() to throw an InputError whose message contains `needle`.
template <class Fn>
void expect_input_error(Fn&& fn, const std::string& needle) {
  try {
    fn();
    ADD_FAILURE() << "no InputError thrown (expected one mentioning '" << needle << "')";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message '" << e.what() << "' lacks '" << needle << "'";
  }
}

ImageF test_mask(int w, int h) {
  ImageF m(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.at(x, y) = float(x * 7 + y * 13 % 17) / 31.0f;
  m.at(0, 0) = 0.0f;
  m.at(1, 0) = 1.0f;
  m.at(2, 0) = std::numeric_limits<float>::denorm_min();  // survives a lossless round trip
  m.at(3, 0) = 0.1f;
  return m;
}

TEST(ImageIo, ExrMaskRoundTripIsBitExact) {
  const ImageF mask = test_mask(37, 23);
  const std::string path = test::binary_path("core/mask_roundtrip.exr");
  write_exr_mask(path, mask);
  const ImageF back = read_exr_mask(path);
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 23);
  ASSERT_EQ(back.channels, 1);
  ASSERT_EQ(back.data.size(), mask.data.size());
  EXPECT_EQ(0, std::memcmp(back.data.data(), mask.data.data(), mask.data.size() * sizeof(float)));
}

TEST(ImageIo, ExrTexelRoundTripIsExact) {
  ImageU32 texels(19, 11);
  for (size_t i = 0; i < texels.data.size(); ++i) texels.data[i] = uint32_t(i * 2654435761u);
  texels.at(0, 0) = kNoTexel;
  texels.at(1, 0) = 0;
  const std::string path = test::binary_path("core/texels_roundtrip.exr");
  write_exr_texels(path, texels);
  const ImageU32 back = read_exr_texels(path);
  ASSERT_EQ(back.width, 19);
  ASSERT_EQ(back.height, 11);
  EXPECT_EQ(back.data, texels.data);
}

TEST(ImageIo, ReadingAMaskAsTexelsIsAnInputError) {
  const std::string path = test::binary_path("core/mask_for_texels.exr");
  write_exr_mask(path, test_mask(4, 3));
  expect_input_error([&] { read_exr_texels(path); }, "texel");
  expect_input_error([&] { read_exr_texels(path); }, path);
}

TEST(ImageIo, ReadingTexelsAsAMaskIsAnInputError) {
  const std::string path = test::binary_path("core/texels_for_mask.exr");
  write_exr_texels(path, ImageU32(4, 3, 1, 5u));
  expect_input_error([&] { read_exr_mask(path); }, "'Y'");
}

// An EXR whose data window does not start at (0, 0) (a crop or an overscan) is refused instead
// of being compared as if it did (metric used to read a window (5,7)-(12,10) as pixels (0,0)-).
TEST(ImageIo, ExrDataWindowMustBeTheWholeImageFromTheOrigin) {
  auto write_window = [](const std::string& name, Imath::Box2i disp, Imath::Box2i data) {
    const std::string path = test::binary_path(name);
    Imf::Header header(disp, data);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    const int w = data.max.x - data.min.x + 1, h = data.max.y - data.min.y + 1;
    std::vector<float> px(size_t(w * h), 0.5f);
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, px.data(), data, sizeof(float), sizeof(float) * size_t(w)));
    file.setFrameBuffer(fb);
    file.writePixels(h);
    return path;
  };
  const Imath::Box2i whole(Imath::V2i(0, 0), Imath::V2i(15, 11));
  EXPECT_EQ(read_exr_mask(write_window("window_whole.exr", whole, whole)).width, 16);
  for (const auto& [name, data] : {std::pair<const char*, Imath::Box2i>{"window_offset.exr", Imath::Box2i(Imath::V2i(5, 7), Imath::V2i(12, 10))},
                                   {"window_crop.exr", Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(7, 5))}}) {
    try {
      read_exr_mask(write_window(name, whole, data));
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("data window"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

// Found by fuzz/fuzz_exr: a 225-byte header whose first attribute declares 1.6 GB made OpenEXR
// allocate (and zero) that much before failing. The attribute sizes are now checked against the
// file first, and a header declaring far more pixels than the file can hold is refused.
TEST(ImageIo, HostileExrHeadersAreRefusedBeforeAllocating) {
  try {
    read_exr_mask(test::source_path("tests/fixtures/exr_huge_attribute.exr"));
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("declares 1634231040 bytes"), std::string::npos) << e.what();
  }
}

// Also found by fuzz/fuzz_exr (a timeout): a channel list whose declared size overruns the
// attributes after it. OpenEXR reads a channel list up to its empty name, not by its size, so a
// walk that trusted the size missed the next attribute, which declared 2 GB.
TEST(ImageIo, ExrHeaderWalkFollowsOpenExrOnChannelLists) {
  try {
    read_exr_rgb(test::source_path("tests/fixtures/exr_chlist_size_mismatch.exr"));
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("declares 2020598114 bytes"), std::string::npos) << e.what();
  }
}

TEST(ImageIo, MissingExrNamesTheFile) {
  const std::string path = test::binary_path("core/does_not_exist.exr");
  std::remove(path.c_str());
  expect_input_error([&] { read_exr_mask(path); }, path + ": cannot open: No such file");
  expect_input_error([&] { read_exr_texels(path); }, "does_not_exist.exr");
}

TEST(ImageIo, GarbageExrIsAnInputError) {
  const std::string path = test::binary_path("core/garbage.exr");
  std::ofstream(path) << "this is not an EXR file";
  expect_input_error([&] { read_exr_mask(path); }, "garbage.exr");
}

TEST(ImageIo, WritingIntoAMissingFolderIsAnInputError) {
  const std::string path = test::binary_path("core/no_such_folder/x/mask.exr");
  std::remove(path.c_str());
  std::remove(test::binary_path("core/no_such_folder/x").c_str());
  expect_input_error([&] { write_exr_mask(path, test_mask(2, 2)); }, "mask.exr");
  expect_input_error([&] { write_png_grey(path + ".png", test_mask(2, 2)); }, "mask.exr.png");
}

TEST(ImageIo, PngGreyIsSrgbEncodedAndReadableByStb) {
  // 0 → 0, 1 → 255, the linear value of sRGB code 128 → 128, NaN → 0, out of range clamps.
  ImageF img(5, 2);
  const float values[5] = {0.0f, 1.0f, srgb8_to_linear(128),
                           std::numeric_limits<float>::quiet_NaN(), 2.0f};
  for (int x = 0; x < 5; ++x) {
    img.at(x, 0) = values[x];
    img.at(x, 1) = -1.0f;
  }
  const std::string path = test::binary_path("core/grey.png");
  write_png_grey(path, img);
  int w = 0, h = 0, comp = 0;
  unsigned char* px = stbi_load(path.c_str(), &w, &h, &comp, 0);
  ASSERT_NE(px, nullptr) << stbi_failure_reason();
  EXPECT_EQ(w, 5);
  EXPECT_EQ(h, 2);
  EXPECT_EQ(comp, 1);
  const int expected[5] = {0, 255, 128, 0, 255};
  for (int x = 0; x < 5; ++x) {
    EXPECT_EQ(int(px[x]), expected[x]) << "x " << x;
    EXPECT_EQ(int(px[5 + x]), 0) << "x " << x;
  }
  stbi_image_free(px);
}

TEST(ImageIo, PngRgbKeepsChannelsAndRows) {
  ImageF img(2, 2, 3);
  img.at(0, 0, 0) = 1.0f;  // top-left red
  img.at(1, 0, 1) = 1.0f;  // top-right green
  img.at(0, 1, 2) = 1.0f;  // bottom-left blue
  const std::string path = test::binary_path("core/rgb.png");
  write_png_rgb(path, img);
  int w = 0, h = 0, comp = 0;
  unsigned char* px = stbi_load(path.c_str(), &w, &h, &comp, 3);
  ASSERT_NE(px, nullptr);
  const int expected[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0};
  for (int i = 0; i < 12; ++i) EXPECT_EQ(int(px[i]), expected[i]) << "byte " << i;
  stbi_image_free(px);
}

TEST(ImageIo, TextureLoadDecodesSrgbColourButNotAlpha) {
  // An RGB PNG (our writer): colour comes back linear (sRGB 128 → 0.2158), alpha 1.
  ImageF img(2, 1, 3);
  img.at(0, 0, 0) = img.at(0, 0, 1) = img.at(0, 0, 2) = srgb8_to_linear(128);
  img.at(1, 0, 0) = 1.0f;
  const std::string path = test::binary_path("core/texture.png");
  write_png_rgb(path, img);
  const ImageF tex = load_texture_rgba(path);
  ASSERT_EQ(tex.channels, 4);
  ASSERT_EQ(tex.width, 2);
  EXPECT_NEAR(tex.at(0, 0, 0), 0.21586f, 1e-5f);  // (128/255 + 0.055)/1.055)^2.4
  EXPECT_FLOAT_EQ(tex.at(1, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(tex.at(1, 0, 1), 0.0f);
  EXPECT_FLOAT_EQ(tex.at(0, 0, 3), 1.0f);  // no alpha in the file: opaque
  expect_input_error([&] { load_texture_rgba(test::binary_path("core/nope.png")); },
                     "nope.png: cannot open");
}

TEST(Texture, AlphaIsStoredNotDecodedAndLookupIsNearestRepeatVUp) {
  const std::string path = test::assets_dir() + "/plants/shrub_diffuse.png";
  const Texture8 t8 = load_texture8(path);
  ASSERT_TRUE(t8.file_has_alpha());
  const ImageF tex = texture_to_linear_rgba(t8);
  // Alpha equals the stored byte / 255 (no sRGB decoding).
  for (int i = 0; i < 50; ++i) {
    const int x = (i * 97) % t8.width, y = (i * 61) % t8.height;
    EXPECT_FLOAT_EQ(tex.at(x, y, 3), float(t8.at(x, y, 3)) / 255.0f);
  }
  // uv (0, 0) is the bottom-left texel, (0.999, 0.999) the top-right one; uv wraps.
  const int w = tex.width, h = tex.height;
  EXPECT_EQ(sample_alpha(tex, vec2(0.0f, 0.0f)), tex.at(0, h - 1, 3));
  EXPECT_EQ(sample_alpha(tex, vec2(0.9999f, 0.9999f)), tex.at(w - 1, 0, 3));
  EXPECT_EQ(sample_alpha(tex, vec2(1.0f + 0.5f / float(w), -1.0f + 0.5f / float(h))),
            tex.at(0, h - 1, 3));
  EXPECT_EQ(sample_alpha(tex, vec2(std::numeric_limits<float>::quiet_NaN(), 0.0f)),
            tex.at(0, h - 1, 3));
}

TEST(Texture, SrgbCurveEndpointsAndInverse) {
  EXPECT_EQ(srgb_to_linear(0.0f), 0.0f);
  EXPECT_NEAR(srgb_to_linear(1.0f), 1.0f, 1e-6f);
  for (int i = 0; i < 256; ++i)
    EXPECT_EQ(int(linear_to_srgb8(srgb8_to_linear(uint8_t(i)))), i) << "code " << i;
}

}  // namespace
}  // namespace shadowlab
