#include "core/assets.h"

#include <filesystem>

#include "core/error.h"

namespace shadowlab {

std::string assets_dir() { return std::string(SHADOWLAB_SOURCE_ROOT) + "/assets"; }

std::string asset_path(const std::string& relative, const std::string& where) {
  const std::string path = assets_dir() + "/" + relative;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(where, "needs the asset " + path + ", which is missing");
  return path;
}

}  // namespace shadowlab
