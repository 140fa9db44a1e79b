// nsm_data (docs/programs/nsm_data.md): the same command gives the same bytes at 1 and 2
// threads, every frame file ends with the FNV-1a of the bytes before it, and bad input is
// refused with one line before any work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/hash.h"
#include "run_process.h"

namespace shadowlab {
// A named namespace: the unity build compiles several test files in one translation unit.
namespace nsm_data_test {

namespace fs = std::filesystem;
using test::ProcResult;

const std::string kSmall = "nsm_data --width 64 --height 48 --crop 32,24 --base-res 64";
const std::string kTiny = kSmall + " --frames 2 --spp 4";

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string fresh(const std::string& name) {
  const std::string d = test::binary_path(name);
  fs::remove_all(d);
  return d;
}

TEST(NsmData, SameBytesAt1And2Threads) {
  std::vector<std::string> dirs;
  for (int t : {1, 2}) {
    const std::string out = fresh("nsm_data_t" + std::to_string(t));
    // A window of 6144 pixels: two of the features' 4096-pixel chunks, 96 ray tiles.
    const ProcResult r = test::run("nsm_data --width 128 --height 96 --crop 96,64 --base-res 64 "
                                   "--frames 2 --spp 4 --threads " + std::to_string(t) + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    dirs.push_back(out);
  }
  for (const char* f : {"manifest.json", "frames/000000.nsmf", "frames/000001.nsmf"}) {
    const std::string a = read_all(dirs[0] + "/" + f), b = read_all(dirs[1] + "/" + f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == b) << f << " differs";
  }
  // The trailing hash covers every byte before it; the frames differ from each other.
  const std::string f0 = read_all(dirs[0] + "/frames/000000.nsmf");
  ASSERT_GT(f0.size(), 64u);
  Fnv1a h;
  h.bytes(f0.data(), f0.size() - 8);
  uint64_t stored = 0;
  std::memcpy(&stored, f0.data() + f0.size() - 8, 8);
  EXPECT_EQ(stored, h.h);
  EXPECT_EQ(f0.substr(0, 4), "NSMF");
  EXPECT_NE(f0, read_all(dirs[0] + "/frames/000001.nsmf"));
  const nlohmann::json m = test::read_json(dirs[0] + "/manifest.json");
  EXPECT_EQ(m["frames"], 2);
  size_t listed = 0;
  for (const char* s : {"train", "val", "test"}) listed += m["splits"][s].size();
  EXPECT_EQ(listed, 2u);
}

TEST(NsmData, HeldOutScenesFormTheTestSplit) {
  const std::string out = fresh("nsm_data_split");
  const ProcResult r = test::run(kSmall + " --frames 3 --spp 1 --radii 0 --scenes plane,default "
                                          "--split-test plane --split-val 0 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json m = test::read_json(out + "/manifest.json");
  // Frames 0 and 2 are the plane's (i mod 2), frame 1 the default scene's.
  EXPECT_EQ(m["splits"]["test"], nlohmann::json({"000000.nsmf", "000002.nsmf"}));
  EXPECT_EQ(m["splits"]["train"], nlohmann::json({"000001.nsmf"}));
  EXPECT_EQ(m["split_scenes"]["test"], nlohmann::json({"plane"}));
}

TEST(NsmData, BadInputIsRefused) {
  const std::string out = " --out " + test::binary_path("nsm_data_bad");
  test::expect_clear_error(kTiny + " --crop 65,24" + out, "nsm_data: --crop: ");
  test::expect_clear_error(kTiny + " --crop 32" + out, "nsm_data: --crop: ");
  test::expect_clear_error(kTiny + " --crop 32,x" + out, "nsm_data: --crop: ");
  test::expect_clear_error(kTiny + " --radii 0,-0.1" + out, "nsm_data: --radii: ");
  test::expect_clear_error(kTiny + " --radii 0.1,0.1" + out, "nsm_data: --radii: ");
  test::expect_clear_error(kTiny + " --spp 0" + out, "nsm_data: --spp: ");
  test::expect_clear_error(kTiny + " --frames 0" + out, "nsm_data: --frames: ");
  test::expect_clear_error(kTiny + " --scenes nosuch" + out, "nosuch");
  test::expect_clear_error(kTiny + " --scenes default,default" + out, "nsm_data: --scenes: ");
  test::expect_clear_error(kTiny + " --split-test bunny" + out, "nsm_data: --split-test: ");
  test::expect_clear_error(kTiny + " --split-val 1.5" + out, "nsm_data: --split-val: ");
  test::expect_clear_error(kTiny + " --split-val 0.6 --split-test 0.6" + out, "nsm_data: --split-val: ");
  test::expect_clear_error(kTiny + " --features d,nosuch" + out, "nsm_data: --features: ");
  test::expect_clear_error(kTiny + " --eye 1,2,3" + out, "nsm_data: --eye: ");
  test::expect_clear_error(kTiny + " --width 5000 --crop 32,24" + out, "nsm_data: --width: ");
  EXPECT_FALSE(fs::exists(test::binary_path("nsm_data_bad")));
}

// --out that cannot be written is refused before hours of work (CPU time capped at 10 s).
TEST(NsmData, UnwritableOutIsRefusedFirst) {
  const std::string d = fresh("nsm_data_out_first");
  fs::create_directories(d);
  std::ofstream(d + "/file") << "x";
  for (const std::string& out : {std::string("/proc/self"), d + "/file/out"}) {
    if (out == "/proc/self" && !fs::is_directory("/proc/self")) continue;
    const std::string cmd = "nsm_data --frames 100000 --spp 65536 --out " + out;
    const ProcResult r = test::run_env("ulimit -t 10;", cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd << "\nstderr: " << r.err;
    EXPECT_EQ(r.err.rfind("nsm_data: --out: ", 0), 0u) << cmd << "\nstderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace nsm_data_test
}  // namespace shadowlab
