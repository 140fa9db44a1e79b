// The folder layering of docs/layout.md, read off the sources' #include lines (every file of
// every source folder and its sub-folders):
//   core       includes only core;
//   util       only core and util;
//   scenes     only core and scenes; nothing in raster, raytrace, metric or techniques
//              includes scenes;
//   lab        anything but programs;
//   python     the Python module: anything but programs (a consumer of lab, as programs are);
//   programs   anything; no other folder includes programs (a main is not library code);
//   Embree's headers only in raytrace.
// Every top-level folder holding sources is one of these (or a consumer: tests, fuzz, peers),
// so a new folder cannot escape the rules unnoticed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "test_paths.h"

namespace shadowlab {
namespace layering {  // a named namespace: the unity build joins the tests of a folder

bool is_source(const std::filesystem::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".h" || ext == ".cpp" || ext == ".inl";
}

// Every `#include "x/..."` (file relative to the folder, included path) and every file that
// includes `<embree...>`, over the folder and all its sub-folders.
struct Includes {
  std::vector<std::pair<std::string, std::string>> quoted;
  std::vector<std::string> embree;
};

Includes read_includes(const std::string& folder) {
  Includes out;
  const std::filesystem::path root = test::source_path(folder);
  for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
    if (!e.is_regular_file() || !is_source(e.path())) continue;
    const std::string file = std::filesystem::relative(e.path(), root).string();
    std::ifstream in(e.path());
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("#include \"", 0) == 0)
        out.quoted.push_back({file, line.substr(10, line.find('"', 10) - 10)});
      if (line.rfind("#include <embree", 0) == 0) out.embree.push_back(file);
    }
  }
  return out;
}

// The folders a file of `folder` may include ("*": any).
std::set<std::string> allowed(const std::string& folder) {
  const std::set<std::string> libraries = {"core", "util", "raster", "raytrace", "metric", "techniques"};
  if (folder == "core") return {"core"};
  if (folder == "util") return {"core", "util"};
  if (folder == "scenes") return {"core", "scenes"};
  if (folder == "lab") {
    std::set<std::string> s = libraries;
    s.insert({"scenes", "lab"});
    return s;
  }
  if (folder == "python") {
    std::set<std::string> s = libraries;
    s.insert({"scenes", "lab", "python"});
    return s;
  }
  if (folder == "programs") return {"*"};
  return libraries;  // raster, raytrace, metric, techniques: no scenes, lab or programs
}

const std::vector<std::string> kFolders = {"core",   "util",       "scenes", "raster", "raytrace",
                                           "metric", "techniques", "lab",    "python",
                                           "programs"};

// The rule of one folder: a list of "file includes path" violations.
std::vector<std::string> violations(const std::string& folder, const Includes& inc) {
  std::vector<std::string> bad;
  const std::set<std::string> ok = allowed(folder);
  for (const auto& [file, path] : inc.quoted) {
    const size_t slash = path.find('/');
    if (slash == std::string::npos) continue;  // same folder or a generated header
    const std::string top = path.substr(0, slash);
    const bool fine = path.find("..") == std::string::npos && (ok.count("*") || ok.count(top));
    if (!fine) bad.push_back(folder + "/" + file + " includes " + path);
  }
  if (folder != "raytrace")
    for (const std::string& f : inc.embree) bad.push_back(folder + "/" + f + " includes Embree");
  return bad;
}

TEST(Layering, FoldersIncludeOnlyWhatTheyDependOn) {
  size_t checked = 0;
  for (const std::string& folder : kFolders) {
    const Includes inc = read_includes(folder);
    for (const std::string& v : violations(folder, inc)) ADD_FAILURE() << v;
    checked += inc.quoted.size();
  }
  EXPECT_GT(checked, 200u);
}

// The rules catch what they forbid: one bad edge per rule, fed as if read from a file.
TEST(Layering, EachRuleRefusesItsForbiddenEdge) {
  const std::vector<std::pair<std::string, std::string>> bad_edges = {
      {"core", "util/bitmap_font.h"},   {"core", "techniques/registry/technique.h"},
      {"util", "lab/cli.h"},            {"util", "scenes/scene_library.h"},
      {"scenes", "raster/pipeline.h"},  {"techniques", "scenes/scene_library.h"},
      {"raster", "lab/cli.h"},          {"techniques", "programs/render.cpp"},
      {"lab", "programs/render.cpp"},   {"lab", "../programs/render.cpp"},
      {"python", "programs/tune.cpp"}};
  for (const auto& [folder, path] : bad_edges) {
    Includes inc;
    inc.quoted.push_back({"x.h", path});
    EXPECT_EQ(violations(folder, inc).size(), 1u) << folder << " including " << path;
  }
  Includes good;
  good.quoted = {{"a.cpp", "lab/cli.h"}, {"b.cpp", "scenes/scene_library.h"}, {"c.cpp", "util/json_read.h"}};
  EXPECT_TRUE(violations("programs", good).empty());
  Includes embree;
  embree.embree.push_back("x.cpp");
  EXPECT_EQ(violations("techniques", embree).size(), 1u);
  EXPECT_TRUE(violations("raytrace", embree).empty());
}

// A source folder outside kFolders would be checked by no rule.
TEST(Layering, EverySourceFolderHasARule) {
  const std::set<std::string> consumers = {"tests", "fuzz", "peers"};
  for (const auto& e : std::filesystem::directory_iterator(test::source_path("."))) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.rfind('.', 0) == 0 || name.rfind("build", 0) == 0 || consumers.count(name))
      continue;
    bool has_sources = false;
    for (const auto& f : std::filesystem::recursive_directory_iterator(e.path()))
      if (f.is_regular_file() && is_source(f.path())) { has_sources = true; break; }
    const bool ruled = std::find(kFolders.begin(), kFolders.end(), name) != kFolders.end();
    if (has_sources && !ruled) ADD_FAILURE() << name << "/ holds sources but has no layering rule (docs/layout.md)";
  }
}

}  // namespace layering
}  // namespace shadowlab
