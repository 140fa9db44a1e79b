#pragma once
// Scratch files of a test (under the build tree) and the InputError a call throws: the helpers
// the bad-input tests share.
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "test_paths.h"

namespace shadowlab::test {

// build/tests/scratch/<folder>/<name>, the folder created.
inline std::string scratch_path(const std::string& folder, const std::string& name) {
  const std::string dir = binary_path("tests/scratch/" + folder);
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

// Writes `text` to scratch_path(folder, name) and returns the path.
inline std::string write_scratch_text(const std::string& folder, const std::string& name,
                                      const std::string& text) {
  const std::string path = scratch_path(folder, name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The InputError of fn(), whole ("path: reason"); empty when none was thrown.
template <class Fn>
std::string input_error(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace shadowlab::test
