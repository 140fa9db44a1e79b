// Outputs end to end (docs/bad_input.md "Output paths", "Outputs appear all together or not at
// all", "The output folder is checked first"): an output never names an input or another output;
// a run's files replace the folder's previous set as a whole or not at all, an interrupt
// included; every program checks --out before its first expensive step.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../test_paths.h"
#include "core/image.h"
#include "core/image_io.h"
#include "programs/run_process.h"

namespace shadowlab {
namespace {

namespace fs = std::filesystem;
using test::expect_clear_error;
using test::ProcResult;
using test::run;
using test::run_env;

std::string read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Every entry under dir (relative path → "dir" or the file's bytes).
std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> s;
  if (!fs::exists(dir)) return s;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string rel = fs::relative(e.path(), dir).string();
    s[rel] = e.is_directory() ? std::string("dir") : read_bytes(e.path().string());
  }
  return s;
}

// Entries of `parent` (recursively) whose name holds `needle`.
std::vector<std::string> entries_with(const std::string& parent, const std::string& needle) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(parent))
    if (e.path().filename().string().find(needle) != std::string::npos) found.push_back(e.path().string());
  return found;
}

// A fresh, empty scratch folder.
std::string scratch(const std::string& name) {
  const std::string dir = test::binary_path("outputs_test/" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

ImageF ramp(int w, int h, float scale) {
  ImageF img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y) = scale * float(x) / float(w - 1);
  return img;
}

const std::string kTinySweep =
    "resolution_sweep --width 64 --height 48 --techniques csm --spp 4 --no-cache";

TEST(Outputs, ContoursNamingAnInputAreRefusedAndTheInputKept) {
  const std::string d = scratch("contours");
  write_exr_mask(d + "/T.exr", ramp(32, 24, 1.0f), {});
  write_exr_mask(d + "/R.exr", ramp(32, 24, 0.5f), {});
  // An EXR under a .png name, and a second name (hard link) of the same file.
  fs::copy_file(d + "/T.exr", d + "/T.png");
  fs::create_hard_link(d + "/T.png", d + "/L.png");
  const std::string t = read_bytes(d + "/T.exr"), tp = read_bytes(d + "/T.png");
  expect_clear_error("metric " + d + "/T.exr " + d + "/R.exr --contours " + d + "/T.exr", "--contours");
  expect_clear_error("metric " + d + "/T.png " + d + "/R.exr --contours " + d + "/T.png",
                     "is an input of this run");
  expect_clear_error("metric " + d + "/T.png " + d + "/R.exr --contours " + d + "/L.png",
                     "is an input of this run");
  // The same file through another spelling of its path.
  expect_clear_error("metric " + d + "/T.png " + d + "/R.exr --contours " + d + "/./sub/../T.png",
                     "is an input of this run");
  EXPECT_EQ(read_bytes(d + "/T.exr"), t);
  EXPECT_EQ(read_bytes(d + "/T.png"), tp);
  EXPECT_EQ(read_bytes(d + "/L.png"), tp);
  // A new .png is written, and nothing else appears beside it.
  const ProcResult ok = run("metric " + d + "/T.exr " + d + "/R.exr --contours " + d + "/C.png");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_GT(read_bytes(d + "/C.png").size(), 8u);
  EXPECT_EQ(snapshot(d).size(), 5u);
}

TEST(Outputs, PlotMustBeAnSvgThatNoOtherOutputNames) {
  const std::string d = scratch("plot");
  const std::string p = d + "/P";
  expect_clear_error(kTinySweep + " --resolutions 64 --out " + p + " --plot " + p + "/sweep.csv", "--plot");
  expect_clear_error(kTinySweep + " --resolutions 64 --out " + p + " --plot " + p + "/csm_64_mask.png", "--plot");
  expect_clear_error(kTinySweep + " --resolutions 64 --out " + p + " --plot " + d + "/plot.png", "--plot");
  expect_clear_error(kTinySweep + " --resolutions 64 --out " + p + " --plot " + p, "--plot");
  EXPECT_FALSE(fs::exists(p));
  EXPECT_FALSE(fs::exists(d + "/plot.png"));
  // A plot inside --out and one beside it are both written, each as an SVG.
  const ProcResult in = run(kTinySweep + " --resolutions 64 --repeats 1 --out " + p + " --plot " + p + "/plot.svg");
  ASSERT_EQ(in.exit_code, 0) << in.err;
  EXPECT_EQ(read_bytes(p + "/plot.svg").rfind("<svg", 0), 0u);
  EXPECT_EQ(read_bytes(p + "/sweep.csv").rfind("# provenance", 0), 0u);
  const ProcResult beside = run(kTinySweep + " --resolutions 64 --repeats 1 --out " + p + " --plot " + d + "/plot.svg");
  ASSERT_EQ(beside.exit_code, 0) << beside.err;
  EXPECT_EQ(read_bytes(d + "/plot.svg").rfind("<svg", 0), 0u);
  EXPECT_TRUE(entries_with(d, ".partial").empty());
  EXPECT_TRUE(entries_with(d, ".staging").empty());
}

TEST(Outputs, RenderIntoAFolderWhereAnOutputNameIsAFolderLeavesItIntact) {
  const std::string a = scratch("render_dir") + "/A";
  fs::create_directories(a + "/shaded.png");
  std::ofstream(a + "/shaded.png/keep.txt") << "kept";
  for (const char* name : {"mask.exr", "mask.png", "texel.exr", "timing.json", "shaded.exr"})
    std::ofstream(a + "/" + name) << "old " << name;
  const auto before = snapshot(a);
  expect_clear_error("render --technique csm:res=64 --width 64 --height 48 --repeats 1 --out " + a,
                     "shaded.png");
  EXPECT_EQ(snapshot(a), before);
  EXPECT_TRUE(entries_with(fs::path(a).parent_path().string(), ".staging").empty());
}

TEST(Outputs, ARerunReplacesThePreviousSetAsAWholeAndKeepsForeignFiles) {
  const std::string d = scratch("rerun") + "/S";
  ASSERT_EQ(run(kTinySweep + " --resolutions 32,64 --repeats 1 --out " + d).exit_code, 0);
  ASSERT_TRUE(fs::exists(d + "/csm_64_mask.png"));
  // The folder has the permissions any new folder gets: all of rwxrwxrwx the umask allows.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  EXPECT_EQ(unsigned(fs::status(d).permissions() & fs::perms::all), unsigned(0777 & ~mask));
  std::ofstream(d + "/notes.txt") << "mine";
  const ProcResult r = run(kTinySweep + " --resolutions 32 --repeats 1 --out " + d);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The new set: no file of the old run that the new one did not write.
  EXPECT_FALSE(fs::exists(d + "/csm_64_mask.png"));
  EXPECT_FALSE(fs::exists(d + "/csm_64_timing.json"));
  EXPECT_TRUE(fs::exists(d + "/csm_32_mask.png"));
  EXPECT_EQ(read_bytes(d + "/notes.txt"), "mine");
  EXPECT_EQ(read_bytes(d + "/sweep.csv").find("CSM 64"), std::string::npos);
}

// --from FILE names an input: a repeat whose --out (given, or the recorded one) would replace
// it is refused before any work.
TEST(Outputs, ARepeatThatWouldReplaceItsFromFileIsRefused) {
  const std::string d = scratch("from") + "/R";
  const std::string render = "render --technique csm:res=64 --width 64 --height 48 --repeats 1 --out " + d;
  ASSERT_EQ(run(render).exit_code, 0);
  const auto before = snapshot(d);
  expect_clear_error("render --from " + d + "/timing.json --out " + d, "timing.json: is an input of this run");
  expect_clear_error("render --from " + d + "/timing.json", "timing.json: is an input of this run");
  EXPECT_EQ(snapshot(d), before);
  const std::string s = scratch("from_sweep") + "/S";
  ASSERT_EQ(run(kTinySweep + " --resolutions 32 --repeats 1 --out " + s).exit_code, 0);
  const auto sweep_before = snapshot(s);
  expect_clear_error("resolution_sweep --from " + s + "/sweep.json", "sweep.json: is an input of this run");
  EXPECT_EQ(snapshot(s), sweep_before);
  // Into another folder the repeat runs.
  EXPECT_EQ(run("render --from " + d + "/timing.json --out " + d + "2").exit_code, 0);
}

// What a crash between the swap's two renames leaves (no --out, its backup and the new set in
// a staging folder, both of a process that no longer exists) is put right by the next run into
// the same --out: the backup becomes --out again, then the run replaces its set as usual.
TEST(Outputs, ACrashBetweenTheTwoRenamesIsRecoveredByTheNextRun) {
  const std::string parent = scratch("crash");
  const std::string d = parent + "/R";
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  int status = 0;
  ASSERT_EQ(waitpid(dead, &status, 0), dead);
  const std::string backup = d + ".old-" + std::to_string(dead);
  const std::string staging = d + ".staging-" + std::to_string(dead);
  fs::create_directories(backup);
  std::ofstream(backup + "/notes.txt") << "previous";
  fs::create_directories(staging);
  std::ofstream(staging + "/mask.png") << "new";
  const ProcResult r = run("render --technique csm:res=64 --width 64 --height 48 --repeats 1 --out " + d);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_bytes(d + "/notes.txt"), "previous");
  EXPECT_GT(read_bytes(d + "/mask.png").size(), 8u);
  EXPECT_FALSE(fs::exists(backup));
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_EQ(std::distance(fs::directory_iterator(parent), fs::directory_iterator()), 1);
}

// Only names of the exact form --out.staging-PID / --out.old-PID, PID at most 10 digits, are a
// crashed run's: folders that merely look alike (no digits, other characters, 11 digits: no
// pid, whatever a cast would make of it) are someone else's and stay.
TEST(Outputs, LookalikesOfACrashedRunsFoldersAreLeftAlone) {
  const std::string parent = scratch("lookalike");
  const std::string d = parent + "/R";
  const std::vector<std::string> others = {d + ".staging-", d + ".staging-12ab", d + ".staging-99999999999",
                                           d + ".old-99999999999"};
  for (const std::string& o : others) {
    fs::create_directories(o);
    std::ofstream(o + "/keep.txt") << "mine";
  }
  const ProcResult r = run("render --technique csm:res=64 --width 64 --height 48 --repeats 1 --out " + d);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& o : others) EXPECT_EQ(read_bytes(o + "/keep.txt"), "mine") << o;
}

// Starts build/programs/<program> with args (stdout and stderr to /dev/null).
pid_t spawn(const std::string& program, const std::vector<std::string>& args) {
  const std::string path = std::string(SHADOWLAB_BINARY_DIR) + "/programs/" + program;
  std::vector<std::string> all = {path};
  all.insert(all.end(), args.begin(), args.end());
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(path.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// A finished sweep into S, then a slow rerun into S ended by `sig` once its first file exists.
void interrupt_a_rerun(int sig, const std::string& name) {
  const std::string parent = scratch(name);
  const std::string d = parent + "/S";
  const std::vector<std::string> args = {"--width", "64", "--height", "48", "--techniques", "csm",
                                         "--resolutions", "64", "--spp", "4", "--no-cache", "--out", d};
  std::vector<std::string> quick = args, slow = args;
  quick.insert(quick.end(), {"--repeats", "1"});
  // Enough timing repeats that the run is still in its first row when it is interrupted (the
  // camera pass before the reference takes as many).
  slow.insert(slow.end(), {"--repeats", "3000"});
  int status = 0;
  const pid_t first = spawn("resolution_sweep", quick);
  ASSERT_EQ(waitpid(first, &status, 0), first);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const auto before = snapshot(d);
  ASSERT_TRUE(before.count("reference_mask.exr"));
  const pid_t pid = spawn("resolution_sweep", slow);
  // Interrupted once a file of the new run exists: in a staging folder beside --out, or in --out.
  bool seen = false;
  for (int i = 0; i < 60000 && !seen; ++i) {
    for (const std::string& s : entries_with(parent, ".staging"))
      if (fs::is_directory(s) && !fs::is_empty(s)) seen = true;
    if (!seen && snapshot(d) != before) seen = true;
    if (!seen) {
      ASSERT_EQ(waitpid(pid, &status, WNOHANG), 0) << "the run ended before it was interrupted";
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  ASSERT_TRUE(seen);
  ASSERT_EQ(kill(pid, sig), 0);
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
  EXPECT_EQ(snapshot(d), before);
  std::string left;
  for (const auto& e : fs::recursive_directory_iterator(parent))
    if (e.path().string().find(d + "/") != 0) left += e.path().string() + " ";
  EXPECT_TRUE(entries_with(parent, ".partial").empty()) << left;
  EXPECT_TRUE(entries_with(parent, ".staging").empty()) << left;
  EXPECT_EQ(std::distance(fs::directory_iterator(parent), fs::directory_iterator()), 1) << left;
}

TEST(Outputs, AnInterruptedSweepLeavesThePreviousFolderAndNoTemporaries) {
  interrupt_a_rerun(SIGINT, "interrupt");
}

TEST(Outputs, ATerminatedSweepLeavesThePreviousFolderAndNoTemporaries) {
  interrupt_a_rerun(SIGTERM, "terminate");
}

// --out that cannot be written: an existing folder no one may create files in (/proc/self, root
// included), and a folder whose parent is a regular file. Each program's arguments ask for work
// that would take hours; CPU time is capped, so a check after that work fails the test.
void expect_out_checked_first(const std::string& program, const std::string& args) {
  const std::string d = scratch("out_first_" + program);
  std::ofstream(d + "/file") << "x";
  const std::string cap = "ulimit -t 10;";
  for (const std::string& out : {std::string("/proc/self"), d + "/file/out"}) {
    if (out == "/proc/self" && !fs::is_directory("/proc/self")) {
      std::printf("skipped: /proc is not mounted\n");
      continue;
    }
    const std::string cmd = program + " " + args + " --out " + out;
    const ProcResult r = run_env(cap, cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd << "\nstderr: " << r.err;
    EXPECT_EQ(r.err.rfind(program + ": --out: ", 0), 0u) << cmd << "\nstderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(read_bytes(d + "/file"), "x");
}

TEST(OutputsOutFirst, Render) {
  expect_out_checked_first("render", "--technique rt:spp=1048576 --no-cache");
}
TEST(OutputsOutFirst, ResolutionSweep) {
  expect_out_checked_first("resolution_sweep", "--spp 1048576 --no-cache");
}
TEST(OutputsOutFirst, Tune) {
  expect_out_checked_first("tune", "--space csm:res=64 --spp 1048576 --no-cache");
}
TEST(OutputsOutFirst, Flicker) {
  expect_out_checked_first("flicker", "--techniques csm --resolutions 64 --frames 100000 --spp 1048576");
}
TEST(OutputsOutFirst, Penumbra) { expect_out_checked_first("penumbra", "--spp 1048576 --points 2048"); }
TEST(OutputsOutFirst, ProjectorMasking) {
  expect_out_checked_first("projector_masking", "--repeats 100000 --no-cache");
}
TEST(OutputsOutFirst, DepthPrecision) {
  expect_out_checked_first("depth_precision", "--spp 1048576 --no-cache");
  // The second case's subfolder is a file: refused before the first case runs.
  const std::string d = scratch("depth_precision_sub");
  std::ofstream(d + "/projector") << "x";
  const ProcResult r = run_env("ulimit -t 10;", "depth_precision --spp 1048576 --no-cache --out " + d);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("projector: is not a folder"), std::string::npos) << r.err;
  EXPECT_EQ(read_bytes(d + "/projector"), "x");
}
TEST(OutputsOutFirst, Merge) {
  const std::string d = scratch("merge_input");
  ASSERT_EQ(run(kTinySweep + " --resolutions 32 --repeats 1 --out " + d).exit_code, 0);
  expect_out_checked_first("merge", d + "/sweep.json");
}
TEST(OutputsOutFirst, MetricContours) {
  // metric has no --out: its one output, --contours, is checked before the metric runs.
  const std::string d = scratch("metric_first");
  write_exr_mask(d + "/T.exr", ramp(1024, 768, 1.0f), {});
  write_exr_mask(d + "/R.exr", ramp(1024, 768, 0.5f), {});
  std::ofstream(d + "/file") << "x";
  for (const std::string& out : {std::string("/proc/self/c.png"), d + "/file/c.png"}) {
    const std::string cmd = "metric " + d + "/T.exr " + d + "/R.exr --repeats 100000 --contours " + out;
    const ProcResult r = run_env("ulimit -t 10;", cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd << "\nstderr: " << r.err;
    EXPECT_EQ(r.err.rfind("metric: --contours: ", 0), 0u) << r.err;
  }
}
TEST(OutputsOutFirst, ProgramsWithoutOutputsRefuseOut) {
  for (const char* p : {"stability", "raster_bench", "technique_bench"})
    expect_clear_error(std::string(p) + " --out /tmp/x", "--out: is not used by this experiment");
}

}  // namespace
}  // namespace shadowlab
