// Every error is exactly one line "<program>: <flag or file>: <reason>" with exit code 2: notes
// about inputs never come before it, JSON read back names the file and the key (never library
// text), a provenance mismatch names the one differing field, list items and flags are named as
// given, and the environment variables follow the rules of the flags they stand for.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/isa.h"
#include "lab/environment.h"
#include "programs/run_process.h"
#include "scenes/gltf_writer.h"
#include "test_paths.h"

namespace shadowlab {
namespace {

using test::expect_clear_error;
using test::ProcResult;
using test::read_json;
using test::run;
using test::run_env;

std::string fresh_dir(const std::string& name) {
  const std::string dir = test::binary_path(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A scene file whose loading says a note (no camera in the file: framed from the bounds) before
// it reaches a bad key in "light"; a glTF file whose light has "range": -1 after the loader's
// notes on which light and camera it uses. Each error is the only line.
TEST(Messages, NotesNeverPrecedeAnError) {
  const std::string dir = fresh_dir("messages_notes");
  std::ofstream(dir + "/tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir + "/bad_key.json")
      << R"({"models": [{"file": "tri.obj"}], "light": {"position": [0, 3, 0], "colour": 1}})";
  expect_clear_error("render --technique csm --scene " + dir + "/bad_key.json --out " + dir + "/o", "colour");

  test::GltfWriter w;
  const int mesh = w.mesh({test::floor_quad(2.0f, 0.0f)});
  w.json["nodes"] = {{{"mesh", mesh}},
                     {{"translation", {0.0, 2.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}};
  w.json["scenes"] = {{{"nodes", {0, 1}}}};
  w.json["scene"] = 0;
  w.json["extensionsUsed"] = {"KHR_lights_punctual"};
  w.json["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"range", -1.0}}};
  w.write(dir + "/range.gltf", true);
  const ProcResult r = run("render --technique csm --scene " + dir + "/range.gltf --out " + dir + "/o2");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find("note:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("range.gltf: light 0: range -1 is not positive"), std::string::npos) << r.err;
}

// A shard file without "kind", and one whose field has the wrong type: one line naming the file
// and the key, no nlohmann text.
TEST(Messages, MergeNamesTheFileAndKeyOfABadField) {
  const std::string dir = fresh_dir("messages_merge");
  std::ofstream(dir + "/nokind.json") << R"({"shard": 0})";
  const ProcResult r = run("merge " + dir + "/nokind.json --out " + dir + "/o");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "merge: " + dir + "/nokind.json: 'kind' is missing\n");
  std::ofstream(dir + "/badtype.json") << R"({"kind": "tune", "scenes": "default"})";
  const ProcResult t = run("merge " + dir + "/badtype.json --out " + dir + "/o");
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_EQ(t.err, "merge: " + dir + "/badtype.json: 'scenes' is not a list of strings\n");
  for (const ProcResult& p : {r, t}) EXPECT_EQ(p.err.find("json.exception"), std::string::npos) << p.err;
}

// Two tune shards whose recorded image width differs: the message names that one field and its
// two values, not the whole provenance.
TEST(Messages, ProvenanceMismatchNamesTheDifferingField) {
  const std::string dir = fresh_dir("messages_provenance");
  for (int i = 0; i < 2; ++i)
    ASSERT_EQ(run("tune --space 'csm:res=16|32' --width 32 --height 24 --spp 1 --repeats 1 --no-cache "
                  "--shard " + std::to_string(i) + "/2 --out " + dir)
                  .exit_code,
              0);
  nlohmann::json s1 = read_json(dir + "/tune_shard1of2.json");
  s1["provenance"]["scenes"][0]["width"] = 33;
  std::ofstream(dir + "/other.json") << s1.dump();
  const ProcResult r = run("merge " + dir + "/tune_shard0of2.json " + dir + "/other.json --out " + dir + "/m");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "merge: " + dir + "/other.json: provenance 'scenes/0/width' differs from " + dir +
                       "/tune_shard0of2.json's (33 vs 32)\n");
}

// A spec a program cannot run is blamed on the flag that gave it: technique_bench's list is
// --techniques; the sweep explains that the ray tracer is its reference, not a row.
TEST(Messages, TechniqueListErrorsNameTheirFlag) {
  expect_clear_error("technique_bench --techniques psm --width 32 --height 24", "technique_bench: --techniques: psm needs a slide projector");
  expect_clear_error("resolution_sweep --quick --techniques rt", "--techniques: rt has no map resolution");
  expect_clear_error("technique_bench --techniques rt", "--techniques: rt has no map resolution");
  expect_clear_error("technique_bench --techniques csm,", "item 2 of 2 is empty (a comma after the last spec)");
}

// SHADOWLAB_THREADS takes --threads' values (an integer in [1, 1024], no spaces, no '+');
// SHADOWLAB_ISA is scalar, avx2 or avx512, no wider than the CPU; SHADOWLAB_SCALAR is 0 or 1.
// Anything else: one line naming the variable, exit code 2, before any work.
TEST(Messages, EnvironmentVariablesFollowTheFlagsRules) {
  const std::string dir = fresh_dir("messages_env");
  const std::string cmd = "render --technique csm:res=32 --width 16 --height 12 --repeats 1 --out " + dir + "/o";
  struct Case {
    const char* env;
    const char* needle;
  };
  for (const Case& c : {Case{"SHADOWLAB_THREADS=' 2'", "render: SHADOWLAB_THREADS: expected an integer, got ' 2'"},
                        Case{"SHADOWLAB_THREADS=+2", "render: SHADOWLAB_THREADS: expected an integer, got '+2'"},
                        Case{"SHADOWLAB_THREADS=0", "render: SHADOWLAB_THREADS: 0 is outside [1, 1024]"},
                        Case{"SHADOWLAB_ISA=sse9", "render: SHADOWLAB_ISA: expected scalar, avx2 or avx512"},
                        Case{"SHADOWLAB_ISA=AVX2", "render: SHADOWLAB_ISA: expected scalar, avx2 or avx512"},
                        Case{"SHADOWLAB_SCALAR=yes", "render: SHADOWLAB_SCALAR: expected 0 or 1, got 'yes'"}}) {
    const ProcResult r = run_env(c.env, cmd);
    EXPECT_EQ(r.exit_code, 2) << c.env << "\n" << r.err;
    EXPECT_EQ(r.err.rfind(c.needle, 0), 0u) << c.env << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.env << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/o")) << c.env;
  }
  // The good values run; an empty value is the variable unset.
  for (const char* env : {"SHADOWLAB_THREADS=2 SHADOWLAB_ISA=avx2 SHADOWLAB_SCALAR=1", "SHADOWLAB_THREADS=",
                          "SHADOWLAB_ISA=scalar"}) {
    const ProcResult ok = run_env(env, cmd);
    EXPECT_EQ(ok.exit_code, 0) << env << "\n" << ok.err;
  }
  // The same rules at the library's own reader (tests and other callers than the programs).
  EXPECT_THROW(check_environment_value("SHADOWLAB_THREADS", "2 "), InputError);
  EXPECT_NO_THROW(check_environment_value("SHADOWLAB_THREADS", "1024"));
  // Every set up to the CPU's widest is taken; a wider one is refused, naming what the CPU runs.
  for (const Isa isa : {Isa::scalar, Isa::avx2, Isa::avx512}) {
    if (isa <= cpu_isa()) {
      EXPECT_NO_THROW(check_environment_value("SHADOWLAB_ISA", isa_name(isa)));
      continue;
    }
    try {
      check_environment_value("SHADOWLAB_ISA", isa_name(isa));
      ADD_FAILURE() << isa_name(isa) << " accepted on a CPU that runs at most " << isa_name(cpu_isa());
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("this CPU runs at most ") + isa_name(cpu_isa())),
                std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace shadowlab
