// libFuzzer target: JSON files read back by the programs (--from's provenance, merge's shard
// files, the same reader as scene files: core/json_file.h). The input is written as f.json and
// read with the result files' limit; an accepted document is then walked whole (dump), which
// recurses once per level. Bad input must be an InputError, never a crash, a hang or an
// allocation beyond the fuzzer's limit.
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/json_file.h"

namespace {

const std::string& folder() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/shadowlab_fuzz_json_XXXXXX";
    return std::string(mkdtemp(tmpl));
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = folder() + "/f.json";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    const nlohmann::json j = shadowlab::read_json_file(path, shadowlab::kResultFileLimit);
    if (j.dump().empty()) __builtin_trap();  // a document always prints as at least one byte
  } catch (const shadowlab::InputError&) {
  }
  return 0;
}
