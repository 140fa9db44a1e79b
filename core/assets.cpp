#include "core/assets.h"

#include <cstdlib>
#include <filesystem>

#include "core/error.h"

namespace shadowlab {

std::string shared_assets_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (const char* env = std::getenv("SHADOWLAB_ASSETS"); env && *env)
    return fs::is_directory(env, ec) ? fs::canonical(env, ec).string() : "";
  for (const fs::path& dir : {fs::path(SHADOWLAB_SOURCE_ROOT) / ".." / "shared" / "assets",
                             fs::path("/work/shared/assets")})
    if (fs::is_directory(dir, ec)) return fs::canonical(dir, ec).string();
  return "";
}

std::string shared_asset_path(const std::string& relative, const std::string& where) {
  const std::string dir = shared_assets_dir();
  if (dir.empty())
    throw InputError(where, "needs the shared assets folder (set SHADOWLAB_ASSETS to it)");
  const std::string path = dir + "/" + relative;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(where, "needs the shared asset " + path + ", which is missing");
  return path;
}

}  // namespace shadowlab
