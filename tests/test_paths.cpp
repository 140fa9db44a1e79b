#include "test_paths.h"

#include <filesystem>

#include "core/assets.h"

namespace shadowlab::test {

std::string source_path(const std::string& relative) {
  return std::string(SHADOWLAB_SOURCE_DIR) + "/" + relative;
}

std::string binary_path(const std::string& relative) {
  const std::string path = std::string(SHADOWLAB_BINARY_DIR) + "/test_output/" + relative;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  return path;
}

std::string assets_dir() { return shadowlab::assets_dir(); }

}  // namespace shadowlab::test
