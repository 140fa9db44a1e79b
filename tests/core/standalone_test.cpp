// The repository stands alone: the assets come from its own assets/ folder, and no source,
// test, script or doc file names a path outside it (a clone elsewhere has no such folder).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/assets.h"
#include "core/error.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

namespace fs = std::filesystem;

TEST(Standalone, AssetsAreTheRepositorysOwnFolder) {
  const fs::path root = fs::canonical(test::source_path(""));
  EXPECT_EQ(fs::path(assets_dir()), root / "assets");
  // Every model a built-in scene, a documented command or a test reads, with its licence.
  for (const char* f : {"bunny/stanford-bunny.obj", "bunny/LICENSE.txt", "palm_tree/palm_tree.obj",
                        "palm_tree/palm_tree.mtl", "palm_tree/leaf_diffus.png",
                        "palm_tree/trunk_diffus.jpg", "palm_tree/LICENSE-nobiax-readme.txt",
                        "plants/parviflora.obj", "plants/fern3.obj", "plants/shrub.obj",
                        "plants/shrub_red.obj", "plants/shrub_diffuse.png",
                        "plants/LICENSE-nobiax-readme.txt", "bench/room100k.obj", "README.md"}) {
    const std::string path = asset_path(f, "test");
    EXPECT_EQ(fs::canonical(path).string().rfind((root / "assets").string() + "/", 0), 0u) << path;
  }
}

TEST(Standalone, AMissingAssetIsOneInputErrorNamingIt) {
  try {
    asset_path("bunny/no-such-model.obj", "--scene bunny");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--scene bunny"), std::string::npos) << what;
    EXPECT_NE(what.find("assets/bunny/no-such-model.obj"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

// Text that names a folder outside the repository: the machines' shared folder, reached
// relatively or absolutely, or anything under the machines' work root. Split so that this file
// does not match.
const std::vector<std::string>& outside_markers() {
  static const std::vector<std::string> m = {std::string("../") + "shared",
                                             std::string("shared/") + "assets",
                                             std::string("shared/") + "peers",
                                             std::string("/") + "work/"};
  return m;
}

// The files a clone carries, minus build trees, outputs and binary data (a NUL byte).
std::vector<fs::path> repository_text_files(const fs::path& root) {
  std::vector<fs::path> out;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    const std::string name = it->path().filename().string();
    const bool skip = name == ".git" || name == "out" || name == ".cache" ||
                      name.rfind("build", 0) == 0;
    if (it->is_directory() && skip && it.depth() == 0) {
      it.disable_recursion_pending();
      continue;
    }
    if (skip && it.depth() == 0) continue;  // the worktree's .git file
    if (it->is_regular_file()) out.push_back(it->path());
  }
  return out;
}

// Every text file counts; a file that must quote an outside path would be listed here.
const std::vector<std::string> kNotScanned = {};

TEST(Standalone, NoFileNamesAPathOutsideTheRepository) {
  const fs::path root = fs::canonical(test::source_path(""));
  const std::vector<fs::path> files = repository_text_files(root);
  ASSERT_GT(files.size(), 100u);  // the walk found the tree
  size_t scanned = 0;
  for (const fs::path& f : files) {
    const std::string rel = fs::relative(f, root).string();
    if (std::find(kNotScanned.begin(), kNotScanned.end(), rel) != kNotScanned.end()) continue;
    std::ifstream in(f, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find('\0') != std::string::npos) continue;
    ++scanned;
    for (const std::string& m : outside_markers())
      for (size_t at = text.find(m); at != std::string::npos; at = text.find(m, at + 1)) {
        const auto end = text.begin() + static_cast<std::ptrdiff_t>(at);
        const size_t line = 1 + size_t(std::count(text.begin(), end, '\n'));
        ADD_FAILURE() << rel << ":" << line << " names a path outside the repository ('" << m
                      << "')";
      }
  }
  EXPECT_GT(scanned, 100u);
}

}  // namespace
}  // namespace shadowlab
