// tune and merge end to end on a tiny image: bad spaces are one-line errors before any work,
// three shards merge to the single process's scores bit for bit, and merge refuses incomplete or
// foreign shard sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "programs/run_process.h"

namespace shadowlab {
namespace {

using test::expect_clear_error;
using test::ProcResult;
using test::read_json;
using test::run;

// 8 points: csm at 3 resolutions × 2 PCF widths, cvsm at 2 resolutions.
const std::string kSmall =
    "tune --space 'csm:res=32..128/x2,pcf=1|3' --space 'cvsm:res=32|64' --width 96 --height 72 "
    "--spp 8 --repeats 1 --threads 2 --budget-ms 1,4,16 --budget-bytes 1e5,1e6 --no-cache";

TEST(TuneMains, BadSpacesAreOneLineErrorsBeforeAnyWork) {
  const std::string out = test::binary_path("tune_bad");
  std::filesystem::remove_all(out);
  const std::string tail = " --width 96 --height 72 --out " + out;
  expect_clear_error("tune --space 'csm:foo=1|2'" + tail, "foo");
  expect_clear_error("tune --space 'csm:res=2048..256/x2'" + tail, "empty range");
  expect_clear_error("tune --space 'csm:res=256..2000/x2'" + tail, "never reach 2000");
  expect_clear_error("tune --space 'csm:res=16..4096/16' --strategy grid --max-evals 100" + tail,
                     "more than --max-evals 100");
  expect_clear_error("tune --space 'csm:res=16..4096/16' --shard 0/2" + tail, "--shard: needs --strategy grid");
  expect_clear_error("tune --space 'csm:res=0|1'" + tail, "'res' = 0 is outside [1, 8192]");
  expect_clear_error("tune --space csm --objective speed" + tail, "unknown objective 'speed'");
  expect_clear_error("tune --space csm --shard 3/3" + tail, "0 <= i < N");
  expect_clear_error("tune --space csm --space csm" + tail, "given twice");
  expect_clear_error("tune --space 'csm:res=64' --space 'csm:res=64|128'" + tail, "occurs in two spaces");
  expect_clear_error("tune --space csm --metric-weights fidelity=0,aesthetics=0,detail=0" + tail, "every weight is 0");
  expect_clear_error("tune --space zsm" + tail, "zsm");
  EXPECT_FALSE(std::filesystem::exists(out)) << "an error came after the output folder was made";
}

TEST(TuneMains, ThreeShardsMergeToTheSingleProcessScores) {
  const std::string dir = test::binary_path("tune_shards");
  std::filesystem::remove_all(dir);
  const ProcResult one = run(kSmall + " --out " + dir + "/single");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("grid: 8 evaluations"), std::string::npos) << one.out;
  for (int i = 0; i < 3; ++i) {
    const ProcResult s = run(kSmall + " --out " + dir + "/shards --shard " + std::to_string(i) + "/3");
    ASSERT_EQ(s.exit_code, 0) << s.err;
  }
  const std::string shards = dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json " +
                             dir + "/shards/tune_shard2of3.json";
  const ProcResult m = run("merge " + shards + " --out " + dir + "/merged");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const nlohmann::json a = read_json(dir + "/single/tune.json");
  const nlohmann::json b = read_json(dir + "/merged/tune.json");
  ASSERT_EQ(a["evaluations"].size(), 8u);
  ASSERT_EQ(b["evaluations"].size(), 8u);
  for (size_t i = 0; i < 8; ++i) {
    const nlohmann::json& x = a["evaluations"][i];
    const nlohmann::json& y = b["evaluations"][i];
    EXPECT_EQ(x["spec"], y["spec"]);
    // Every score, bit for bit (JSON numbers round-trip doubles exactly); times are measured
    // anew by each process and may differ.
    for (const char* k : {"objective", "c10", "c50", "c90", "dark", "lit", "acne", "noise", "detail",
                          "fidelity", "aesthetics", "total", "ssim", "rmse", "psnr"})
      EXPECT_EQ(x[k].get<double>(), y[k].get<double>()) << x["spec"] << " " << k;
    EXPECT_EQ(x["work"], y["work"]) << x["spec"];
  }
  EXPECT_TRUE(std::filesystem::exists(dir + "/merged/tune.svg"));
  EXPECT_NE(m.out.find("Pareto front"), std::string::npos);

  // Incomplete, repeated and foreign shard sets are refused with the file named.
  expect_clear_error("merge " + dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json --out " + dir + "/x",
                     "is one of 3 shards, 2 files given");
  expect_clear_error("merge " + dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json " + dir +
                         "/shards/tune_shard1of3.json --out " + dir + "/x",
                     "shard 1 given twice");
  nlohmann::json foreign = read_json(dir + "/shards/tune_shard2of3.json");
  foreign["provenance"]["scenes"][0]["hash"] = "0000000000000000";
  std::ofstream(dir + "/shards/foreign.json") << foreign.dump();
  expect_clear_error("merge " + dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json " + dir +
                         "/shards/foreign.json --out " + dir + "/x",
                     "provenance 'scenes/0/hash' differs from " + dir + "/shards/tune_shard0of3.json's (\"0000000000000000\" vs \"");
  nlohmann::json other = read_json(dir + "/shards/tune_shard2of3.json");
  other["config"]["spp"] = 9;
  std::ofstream(dir + "/shards/other.json") << other.dump();
  expect_clear_error("merge " + dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json " + dir +
                         "/shards/other.json --out " + dir + "/x",
                     "different configuration");
  // Wrong types in a shard file are one-line errors, not exit 1 or a float-to-integer cast.
  nlohmann::json huge = read_json(dir + "/shards/tune_shard2of3.json");
  huge["evaluations"][0]["index"] = 1e30;
  std::ofstream(dir + "/shards/huge.json") << huge.dump();
  expect_clear_error("merge " + dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json " + dir +
                         "/shards/huge.json --out " + dir + "/x",
                     "'index' is missing or not a whole number");
  // A shard id outside 0..N-1 is refused by name, even for a file with no evaluations to check.
  nlohmann::json beyond = read_json(dir + "/shards/tune_shard2of3.json");
  beyond["shard"] = 3;
  beyond["evaluations"] = nlohmann::json::array();
  std::ofstream(dir + "/shards/beyond.json") << beyond.dump();
  expect_clear_error("merge " + dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json " + dir +
                         "/shards/beyond.json --out " + dir + "/x",
                     "beyond.json: 'shard' = 3 is too large");
  nlohmann::json noconfig = read_json(dir + "/shards/tune_shard0of3.json");
  noconfig.erase("config");
  std::ofstream(dir + "/shards/noconfig.json") << noconfig.dump();
  expect_clear_error("merge " + dir + "/shards/noconfig.json " + dir + "/shards/tune_shard1of3.json " + dir +
                         "/shards/tune_shard2of3.json --out " + dir + "/x",
                     "noconfig.json: 'config' is missing");
  // The merged result repeats the whole run: its command has no --shard and no --out.
  const std::vector<std::string> merged_cmd = b["provenance"]["command"];
  EXPECT_EQ(std::count(merged_cmd.begin(), merged_cmd.end(), "--shard"), 0);
  EXPECT_EQ(std::count(merged_cmd.begin(), merged_cmd.end(), "--out"), 0);
  // --from=FILE is --from FILE (--flag=value works for every flag: docs/programs/common_flags.md):
  // the same file's checks answer, here its --out given as --out= beside a flag --from does not
  // allow.
  expect_clear_error("tune --from=" + dir + "/merged/tune.json --out=" + dir + "/x --spp 3",
                     "--from: only --out DIR and --threads N may be given with --from, got '--spp'");
  nlohmann::json missing = read_json(dir + "/shards/tune_shard2of3.json");
  missing["evaluations"].erase(0);
  std::ofstream(dir + "/shards/missing.json") << missing.dump();
  expect_clear_error("merge " + dir + "/shards/tune_shard0of3.json " + dir + "/shards/tune_shard1of3.json " + dir +
                         "/shards/missing.json --out " + dir + "/x",
                     "missing");
}

TEST(TuneMains, HalvingRunsTwoRungsAndReportsThem) {
  const std::string dir = test::binary_path("tune_halving");
  std::filesystem::remove_all(dir);
  // 9 csm points; eta 3 keeps at least 3 for the full size. Rung 0 is 1/4 per axis, at least 16
  // pixels: 96 × 56 gives 24 × 16 (not 14).
  const ProcResult r = run(
      "tune --space 'csm:res=32..128/x2,pcf=1|3|5' --strategy halving --width 96 --height 56 --spp 8 "
      "--repeats 1 --threads 2 --budget-ms 16 --no-cache --out " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("successive halving: rung 0 ran 9 evaluations at 1/4"), std::string::npos) << r.out;
  const nlohmann::json j = read_json(dir + "/tune.json");
  size_t rung0 = 0, rung1 = 0;
  for (const nlohmann::json& e : j["evaluations"]) {
    (e["rung"] == 0 ? rung0 : rung1)++;
    EXPECT_EQ(e["width"].get<int>(), e["rung"] == 0 ? 24 : 96);
    EXPECT_EQ(e["height"].get<int>(), e["rung"] == 0 ? 16 : 56);
  }
  EXPECT_EQ(rung0, 9u);
  EXPECT_GE(rung1, 3u);
  EXPECT_LT(rung1, 9u);
}

// resolution_sweep --shard: three shards merge to the single process's rows, bit for bit.
TEST(TuneMains, SweepShardsMergeToTheSingleProcessScores) {
  const std::string dir = test::binary_path("sweep_shards");
  std::filesystem::remove_all(dir);
  const std::string cmd = "resolution_sweep --quick --width 64 --height 48 --resolutions 32,64 "
                          "--techniques csm,cvsm,tsm --spp 8 --no-cache --threads 2";
  ASSERT_EQ(run(cmd + " --out " + dir + "/single").exit_code, 0);
  std::string files;
  for (int i = 0; i < 3; ++i) {
    const ProcResult s = run(cmd + " --out " + dir + "/shards --shard " + std::to_string(i) + "/3");
    ASSERT_EQ(s.exit_code, 0) << s.err;
    files += " " + dir + "/shards/sweep_shard" + std::to_string(i) + "of3.json";
  }
  const ProcResult m = run("merge" + files + " --out " + dir + "/merged");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const nlohmann::json a = read_json(dir + "/single/sweep.json"), b = read_json(dir + "/merged/sweep.json");
  ASSERT_EQ(a["rows"].size(), 6u);
  ASSERT_EQ(b["rows"].size(), 6u);
  EXPECT_EQ(b["shard"], 0);  // the merged result is one whole run: shard 0 of 1
  EXPECT_EQ(b["shards"], 1);
  for (size_t i = 0; i < 6; ++i)
    for (const char* k : {"spec", "c10", "c50", "c90", "dark", "lit", "acne", "noise", "detail", "fidelity",
                          "aesthetics", "ssim", "rmse", "psnr", "work"})
      EXPECT_EQ(a["rows"][i][k], b["rows"][i][k]) << i << " " << k;
  EXPECT_TRUE(std::filesystem::exists(dir + "/merged/plot.svg"));
  expect_clear_error("merge " + dir + "/shards/sweep_shard0of3.json --out " + dir + "/x", "is one of 3 shards, 1 files given");
  // A shard of another run is refused naming both files: the one that differs and the first.
  nlohmann::json foreign = read_json(dir + "/shards/sweep_shard2of3.json");
  foreign["provenance"]["scenes"][0]["hash"] = "0000000000000000";
  std::ofstream(dir + "/shards/foreign.json") << foreign.dump();
  expect_clear_error("merge " + dir + "/shards/sweep_shard0of3.json " + dir + "/shards/sweep_shard1of3.json " + dir +
                         "/shards/foreign.json --out " + dir + "/x",
                     dir + "/shards/foreign.json: provenance 'scenes/0/hash' differs from " + dir +
                         "/shards/sweep_shard0of3.json's (\"0000000000000000\" vs \"");
  expect_clear_error(cmd + " --suite hard --shard 0/2 --out " + dir + "/x", "--shard: not with --suite");
}

}  // namespace
}  // namespace shadowlab
