// libFuzzer target: OBJ + MTL text. The input is split at its first NUL byte into the OBJ text
// and the MTL text (the way tinyobjloader's own fuzz target splits it); both are written to a
// private folder and loaded through the same path as --scene file.obj. Bad input must be an
// InputError, never a crash, a hang or an allocation beyond the fuzzer's limit.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scenes/obj_loader.h"

namespace {

const std::string& folder() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/shadowlab_fuzz_obj_XXXXXX";
    return std::string(mkdtemp(tmpl));
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string in(reinterpret_cast<const char*>(data), size);
  const size_t nul = in.find('\0');
  const std::string obj = in.substr(0, nul);
  const std::string mtl = nul == std::string::npos ? "" : in.substr(nul + 1);
  const std::string obj_path = folder() + "/f.obj";
  std::ofstream(obj_path, std::ios::binary) << "mtllib f.mtl\n" << obj;
  std::ofstream(folder() + "/f.mtl", std::ios::binary) << mtl;
  try {
    std::vector<std::string> notes;
    shadowlab::load_obj_scene(obj_path, &notes);
    shadowlab::read_obj_view_header(obj_path);
  } catch (const shadowlab::InputError&) {
  }
  return 0;
}
