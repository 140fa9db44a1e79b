// libFuzzer target: the EXR readers the metric program uses (a mask with channel Y, a texel
// image with channel texel) and the slide reader (RGB), on arbitrary file bytes. Bad input must
// be an InputError, never a crash or a huge allocation.
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/image_io.h"

namespace {

const std::string& path() {
  static const std::string p = [] {
    char tmpl[] = "/tmp/shadowlab_fuzz_exr_XXXXXX";
    return std::string(mkdtemp(tmpl)) + "/f.exr";
  }();
  return p;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::ofstream(path(), std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  for (int kind = 0; kind < 3; ++kind) {
    try {
      if (kind == 0) shadowlab::read_exr_mask(path());
      if (kind == 1) shadowlab::read_exr_texels(path());
      if (kind == 2) shadowlab::read_exr_rgb(path());
    } catch (const shadowlab::InputError&) {
    }
  }
  return 0;
}
