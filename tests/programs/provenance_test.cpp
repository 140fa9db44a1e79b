// Provenance end to end: every output format records it, --from repeats a run's scores exactly,
// and refuses a scene whose file changed since.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "programs/run_process.h"

namespace shadowlab {
namespace {

using test::expect_clear_error;
using test::ProcResult;
using test::read_json;
using test::run;

std::string first_line(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  return line;
}

void expect_provenance(const nlohmann::json& p, const std::string& program, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(p.at("program"), program);
  EXPECT_FALSE(p.at("commit").get<std::string>().empty());
  EXPECT_FALSE(p.at("cpu").get<std::string>().empty());
  EXPECT_FALSE(p.at("version").get<std::string>().empty());
  EXPECT_TRUE(std::regex_match(p.at("date").get<std::string>(),
                               std::regex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z")));
  EXPECT_GE(p.at("threads").get<int>(), 1);
  EXPECT_TRUE(p.at("command").is_array());
  ASSERT_GE(p.at("scenes").size(), 1u);
  const nlohmann::json& s = p.at("scenes")[0];
  EXPECT_TRUE(std::regex_match(s.at("hash").get<std::string>(), std::regex("[0-9a-f]{16}")));
  EXPECT_EQ(s.at("light_position").size(), 3u);
  EXPECT_TRUE(s.at("light_radius").is_number());
  EXPECT_TRUE(p.contains("spp") && p.contains("repeats") && p.contains("seeds"));
}

TEST(Provenance, EveryOutputFormatRecordsIt) {
  const std::string dir = test::binary_path("provenance");
  std::filesystem::remove_all(dir);
  ASSERT_EQ(run("render --technique csm --width 64 --height 48 --repeats 1 --out " + dir + "/render").exit_code, 0);
  const nlohmann::json timing = read_json(dir + "/render/timing.json");
  expect_provenance(timing.at("provenance"), "render", "timing.json");
  for (const char* exr : {"mask.exr", "texel.exr", "shaded.exr"}) {
    std::map<std::string, std::string> attrs;
    for (const auto& [k, v] : read_exr_attributes(dir + "/render/" + exr)) attrs[k] = v;
    EXPECT_EQ(attrs["shadowlab:commit"], timing["provenance"]["commit"]) << exr;
    EXPECT_EQ(attrs["shadowlab:program"], "render") << exr;
    EXPECT_EQ(attrs["shadowlab:technique"], "csm") << exr;
    EXPECT_EQ(nlohmann::json::parse(attrs["shadowlab:scenes"]), timing["provenance"]["scenes"]) << exr;
  }
  ASSERT_EQ(run("resolution_sweep --quick --width 64 --height 48 --resolutions 32 --no-cache --out " + dir + "/sweep").exit_code, 0);
  const nlohmann::json sweep = read_json(dir + "/sweep/sweep.json");
  expect_provenance(sweep.at("provenance"), "resolution_sweep", "sweep.json");
  EXPECT_EQ(sweep["provenance"]["spp"], 64);
  const std::string line = first_line(dir + "/sweep/sweep.csv");
  ASSERT_EQ(line.rfind("# provenance ", 0), 0u) << line;
  EXPECT_EQ(nlohmann::json::parse(line.substr(13)), sweep["provenance"]);
  expect_provenance(read_json(dir + "/sweep/csm_32_timing.json").at("provenance"), "resolution_sweep", "sweep timing");
  ASSERT_EQ(run("tune --space 'csm:res=32|64' --width 64 --height 48 --spp 4 --repeats 1 --no-cache --out " + dir + "/tune").exit_code, 0);
  const nlohmann::json tune = read_json(dir + "/tune/tune.json");
  expect_provenance(tune.at("provenance"), "tune", "tune.json");
  const std::string tline = first_line(dir + "/tune/tune.csv");
  ASSERT_EQ(tline.rfind("# provenance ", 0), 0u) << tline;
  EXPECT_EQ(nlohmann::json::parse(tline.substr(13)), tune["provenance"]);
}

TEST(Provenance, FromRepeatsTheScoresExactly) {
  const std::string dir = test::binary_path("provenance_from");
  std::filesystem::remove_all(dir);
  ASSERT_EQ(run("resolution_sweep --quick --width 64 --height 48 --resolutions 32,64 --techniques csm:pcf=3,cvsm "
                "--spp 8 --no-cache --out " + dir + "/a").exit_code, 0);
  const ProcResult again = run("resolution_sweep --from " + dir + "/a/sweep.json --out " + dir + "/b");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const nlohmann::json a = read_json(dir + "/a/sweep.json"), b = read_json(dir + "/b/sweep.json");
  ASSERT_EQ(a["rows"].size(), 4u);
  ASSERT_EQ(b["rows"].size(), 4u);
  // Every score that does not depend on the measured time, bit for bit.
  for (size_t i = 0; i < 4; ++i)
    for (const char* k : {"spec", "c10", "c50", "c90", "dark", "lit", "acne", "noise", "detail", "fidelity",
                          "aesthetics", "ssim", "rmse", "psnr"})
      EXPECT_EQ(a["rows"][i][k], b["rows"][i][k]) << i << " " << k;
  // The repeat records its own program and command: the recorded one with the new --out.
  EXPECT_EQ(b["provenance"]["program"], "resolution_sweep");
  std::vector<std::string> cmd = a["provenance"]["command"];
  cmd[std::find(cmd.begin(), cmd.end(), "--out") - cmd.begin() + 1] = dir + "/b";
  std::vector<std::string> got = b["provenance"]["command"];
  std::sort(cmd.begin(), cmd.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, cmd);
  expect_clear_error("resolution_sweep --from " + dir + "/a/sweep.json --spp 4", "only --out DIR and --threads N");
  expect_clear_error("tune --from " + dir + "/a/sweep.json", "records a run of resolution_sweep, not tune");
  expect_clear_error("resolution_sweep --from " + dir + "/a/contact_sheet.png", "has no provenance");
  expect_clear_error("resolution_sweep --from", "--from");
}

TEST(Provenance, FromRefusesASceneWhoseFileChanged) {
  const std::string dir = test::binary_path("provenance_changed");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string obj = dir + "/tri.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  ASSERT_EQ(run("render --technique csm --scene " + obj + " --ground --width 32 --height 24 --repeats 1 --out " + dir + "/a").exit_code, 0);
  ASSERT_EQ(run("render --from " + dir + "/a/timing.json --out " + dir + "/b").exit_code, 0);
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1.5 0\nf 1 2 3\n";
  expect_clear_error("render --from " + dir + "/a/timing.json --out " + dir + "/c", "is not the recorded one");
  EXPECT_FALSE(std::filesystem::exists(dir + "/c"));
}

// --from=FILE and --out=DIR beside it are the two-word forms (docs/programs/common_flags.md:
// --flag=value works for every flag).
TEST(Provenance, FromTakesTheEqualsForm) {
  const std::string dir = test::binary_path("provenance_from_equals");
  std::filesystem::remove_all(dir);
  ASSERT_EQ(run("render --technique csm:res=64 --width 32 --height 24 --repeats 1 --out " + dir + "/a").exit_code, 0);
  const ProcResult r = run("render --from=" + dir + "/a/timing.json --out=" + dir + "/b");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json b = read_json(dir + "/b/timing.json");
  std::vector<std::string> cmd = b["provenance"]["command"];
  EXPECT_NE(std::find(cmd.begin(), cmd.end(), "csm:res=64"), cmd.end());
  expect_clear_error("render --from=", "--from: needs a file");
}

}  // namespace
}  // namespace shadowlab
