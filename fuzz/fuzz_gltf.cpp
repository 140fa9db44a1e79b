// libFuzzer target: glTF 2.0. An input starting with "glTF" is written as f.glb, any other as
// f.gltf (JSON; its buffers are data URIs or absent: a relative URI names a file that does not
// exist), and loaded through the same path as --scene f.gltf with every light and camera
// choice the file offers up to 2. Bad input must be an InputError, never a crash, a hang or an
// allocation beyond the fuzzer's limit.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scenes/gltf_loader.h"

namespace {

const std::string& folder() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/shadowlab_fuzz_gltf_XXXXXX";
    return std::string(mkdtemp(tmpl));
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = folder() + (glb ? "/f.glb" : "/f.gltf");
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  for (int choice = 0; choice < 2; ++choice) {
    try {
      std::vector<std::string> notes;
      shadowlab::GltfChoice c;
      c.light = choice;
      c.camera = choice;
      shadowlab::make_gltf_scene(path, c, &notes);
    } catch (const shadowlab::InputError&) {
    }
  }
  return 0;
}
