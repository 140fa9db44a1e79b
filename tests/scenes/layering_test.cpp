// The folder layering of docs/layout.md, read off the sources' #include lines: core includes
// only core; scenes only core and scenes; nothing in raster, raytrace, metric or techniques
// includes scenes; Embree's headers only in raytrace.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_paths.h"

namespace shadowlab {
namespace {

// Every `#include "x/..."` folder (x) and every `#include <embree...>` of the folder's files,
// its sub-folders' included (techniques/ is in sub-folders by role, docs/layout.md).
struct Includes {
  std::vector<std::pair<std::string, std::string>> quoted;  // (file, included path)
  std::vector<std::string> embree;                          // files including Embree
};

Includes read_includes(const std::string& folder) {
  Includes out;
  const std::filesystem::path root = test::source_path(folder);
  for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
    const std::string ext = e.path().extension().string();
    if (ext != ".h" && ext != ".cpp" && ext != ".inl") continue;
    std::ifstream in(e.path());
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("#include \"", 0) == 0)
        out.quoted.push_back({std::filesystem::relative(e.path(), root).generic_string(),
                              line.substr(10, line.find('"', 10) - 10)});
      if (line.rfind("#include <embree", 0) == 0)
        out.embree.push_back(std::filesystem::relative(e.path(), root).generic_string());
    }
  }
  return out;
}

std::string top(const std::string& include) { return include.substr(0, include.find('/')); }

TEST(Layering, FoldersIncludeOnlyWhatTheyDependOn) {
  size_t checked = 0;
  for (const char* folder : {"core", "scenes", "raster", "raytrace", "metric", "techniques"}) {
    const Includes inc = read_includes(folder);
    for (const auto& [file, path] : inc.quoted) {
      const std::string t = top(path);
      const std::string where = std::string(folder) + "/" + file + " includes " + path;
      if (std::string(folder) == "core") {
        EXPECT_EQ(t, "core") << where;
      }
      if (std::string(folder) == "scenes") {
        EXPECT_TRUE(t == "core" || t == "scenes") << where;
      }
      if (std::string(folder) != "scenes") {
        EXPECT_NE(t, "scenes") << where;
      }
      ++checked;
    }
    if (std::string(folder) != "raytrace")
      for (const std::string& f : inc.embree) ADD_FAILURE() << folder << "/" << f << " includes Embree";
  }
  EXPECT_GT(checked, 200u);
}

}  // namespace
}  // namespace shadowlab
