// libFuzzer target: the JSON scene file. The input is written as f.json beside a one-triangle
// t.obj (so "models" can name a real file) and loaded through the same path as --scene f.json.
// Bad input must be an InputError, never a crash, a hang or an allocation beyond the fuzzer's
// limit.
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scenes/scene_file.h"

namespace {

const std::string& folder() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/shadowlab_fuzz_scene_XXXXXX";
    std::string d(mkdtemp(tmpl));
    std::ofstream(d + "/t.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = folder() + "/f.json";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    std::vector<std::string> notes;
    shadowlab::load_scene_file(path, &notes);
  } catch (const shadowlab::InputError&) {
  }
  return 0;
}
