// The documentation's statements that are not generated, checked against the programs and the
// registries they come from: the --scene list of docs/programs/common_flags.md, the layouts and
// filters of the README and docs/overview.md, the metric's --json keys on
// docs/programs/metric.md; --help's registry line; flicker's stated default size;
// docs/design.md's modules.
// (docs/command_line.md is generated and has its own test.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "programs/run_process.h"
#include "scenes/scene_registry.h"
#include "techniques/registry/technique.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

using test::read_json;
using test::run;

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The line of the document `doc` (a path in the source tree) that starts with `prefix` (after
// leading spaces), else "".
std::string doc_line(const std::string& doc, const std::string& prefix) {
  std::istringstream in(read_text(test::source_path(doc)));
  std::string line;
  while (std::getline(in, line)) {
    const size_t start = line.find_first_not_of(' ');
    if (start != std::string::npos && line.compare(start, prefix.size(), prefix) == 0) return line;
  }
  return "";
}

std::vector<std::string> split_words(const std::string& s) {
  std::vector<std::string> out(1);
  for (char c : s)
    if (c == '/') out.emplace_back();
    else out.back() += c;
  return out;
}

// Every `word` in backticks of `text`.
std::set<std::string> backticked(const std::string& text) {
  std::set<std::string> out;
  const std::regex re("`([^`]+)`");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    out.insert((*it)[1].str());
  return out;
}

// The layouts and filters as the registry's names show them: every technique but rt is a layout
// letter + a filter suffix, and every pair is registered.
void registry_layouts_filters(std::set<std::string>& layouts, std::set<std::string>& filters) {
  for (const auto& [name, description] : technique_list()) {
    if (name == "rt" || name == "rts" || name == "nsm") continue;  // outside the layout × filter grid
    layouts.insert(name.substr(0, 1));
    filters.insert(name.substr(1));
  }
}

TEST(DocsMatch, CommonFlagsSceneListIsEveryBuiltInScene) {
  const std::string line = doc_line("docs/programs/common_flags.md", "- `--scene S`:");
  ASSERT_FALSE(line.empty()) << "docs/programs/common_flags.md has no '- `--scene S`:' line";
  const size_t open = line.find("a built-in name ("), close = line.find(';', open);
  ASSERT_NE(open, std::string::npos) << line;
  const std::set<std::string> listed = backticked(line.substr(open, close - open));
  const std::vector<std::string> names = builtin_scene_names();
  EXPECT_EQ(listed, std::set<std::string>(names.begin(), names.end())) << line;
  // --help names the same scenes (both come from the registry; the page must follow).
  const std::string help = run("render --help").out;
  for (const std::string& n : names) EXPECT_NE(help.find(n), std::string::npos) << n;
  EXPECT_NE(line.find("`.json` scene file"), std::string::npos) << line;
}

// The filters of the list techniques/filters/all.h: the folder of each line, which is named by
// the filter's technique suffix.
std::set<std::string> listed_filters() {
  std::ifstream f(test::source_path("techniques/filters/all.h"));
  std::set<std::string> out;
  const std::regex re("#include \"techniques/filters/([a-z0-9_]+)/\\1\\.h\"");
  std::smatch m;
  for (std::string line; std::getline(f, line);)
    if (std::regex_match(line, m, re)) out.insert(m[1].str());
  return out;
}

TEST(DocsMatch, ReadmeAndOverviewLayoutsAndFiltersAreTheRegistrys) {
  std::set<std::string> layouts, filters;
  registry_layouts_filters(layouts, filters);
  ASSERT_EQ(layouts.size(), 4u);
  const std::set<std::string> listed = listed_filters();
  ASSERT_FALSE(listed.empty()) << "techniques/filters/all.h lists no filter";
  ASSERT_EQ(filters, listed) << "the registry's filters are not those of techniques/filters/all.h";
  const std::string count = std::to_string(layouts.size()) + " × " + std::to_string(filters.size()) +
                            " = " + std::to_string(layouts.size() * filters.size()) + " techniques";
  for (const char* doc : {"README.md", "docs/overview.md"}) {
    EXPECT_EQ(backticked(doc_line(doc, "- layouts:")), layouts) << doc << ": " << doc_line(doc, "- layouts:");
    EXPECT_EQ(backticked(doc_line(doc, "- filters:")), filters) << doc << ": " << doc_line(doc, "- filters:");
    EXPECT_NE(doc_line(doc, "- so ").find(count), std::string::npos) << doc << ": " << doc_line(doc, "- so ");
  }
}

// The line above the registry in every --help states the naming rule with every layout letter
// and every filter.
TEST(DocsMatch, HelpRegistryLineNamesEveryLayoutAndFilter) {
  std::set<std::string> layouts, filters;
  registry_layouts_filters(layouts, filters);
  for (const char* program : {"render", "resolution_sweep", "tune", "flicker", "technique_bench"}) {
    const std::string help = run(std::string(program) + " --help").out;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(help, m, std::regex("a layout letter ([a-z/]+) \\+ a filter ([a-z/]+)")))
        << program;
    std::set<std::string> l, f;
    for (const std::string& x : split_words(m[1].str())) l.insert(x);
    for (const std::string& x : split_words(m[2].str())) f.insert(x);
    EXPECT_EQ(l, layouts) << program;
    EXPECT_EQ(f, filters) << program;
  }
}

// Every key of `metric --json` is in the list of them on the metric program's page.
TEST(DocsMatch, MetricPageListsEveryMetricJsonKey) {
  const std::string exr = test::source_path("tests/golden/csm_default_160x120.exr");
  const test::ProcResult r = run("metric " + exr + " " + exr + " --json --shadow-ms 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const std::string line = doc_line("docs/programs/metric.md", "- **`build/programs/metric");
  ASSERT_FALSE(line.empty());
  const size_t keys = line.find("with the keys");
  ASSERT_NE(keys, std::string::npos) << line;
  const std::string listed = line.substr(keys);
  for (auto it = j.begin(); it != j.end(); ++it)
    EXPECT_NE(listed.find(it.key()), std::string::npos) << "docs/programs/metric.md lacks metric --json key " << it.key();
}

// flicker's --help states the image size the program renders without --width/--height.
TEST(DocsMatch, FlickerHelpDefaultSizeIsWhatItRenders) {
  const std::string help = run("flicker --help").out;
  std::smatch w, h;
  ASSERT_TRUE(std::regex_search(help, w, std::regex("--width W +image width in pixels \\(default ([0-9]+)")));
  ASSERT_TRUE(std::regex_search(help, h, std::regex("--height H +image height in pixels \\(default ([0-9]+)")));
  const std::string dir = test::binary_path("docs_flicker_size");
  std::filesystem::remove_all(dir);
  const test::ProcResult r = run("flicker --scene plane --techniques csm --resolutions 16 --frames 2 --spp 1 "
                                 "--out " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json scene = read_json(dir + "/flicker.json")["provenance"]["scenes"][0];
  EXPECT_EQ(scene["width"].get<int>(), std::stoi(w[1].str()));
  EXPECT_EQ(scene["height"].get<int>(), std::stoi(h[1].str()));
}

// docs/design.md §3 puts each loader in the folder that holds it.
TEST(DocsMatch, DesignModulesNameTheFoldersThatHoldTheLoaders) {
  const std::string design = read_text(test::source_path("docs/design.md"));
  const size_t core = design.find("- `core`:"), next = design.find("\n- `", core + 1);
  ASSERT_NE(core, std::string::npos);
  const std::string core_text = design.substr(core, next - core);
  EXPECT_EQ(core_text.find("OBJ"), std::string::npos) << core_text;
  EXPECT_EQ(core_text.find("built-in scenes"), std::string::npos) << core_text;
  EXPECT_TRUE(std::filesystem::exists(test::source_path("scenes/obj_loader.cpp")));
  EXPECT_TRUE(std::filesystem::exists(test::source_path("scenes/scene_registry.cpp")));
  const size_t scenes = design.find("- `scenes`:");
  ASSERT_NE(scenes, std::string::npos);
  EXPECT_NE(design.find("OBJ", scenes), std::string::npos);
}

}  // namespace
}  // namespace shadowlab
