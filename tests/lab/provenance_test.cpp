// The recorded command's editing (lab/provenance.h): the flags a merge or a repeat drops.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <fstream>

#include "core/error.h"
#include "lab/provenance.h"
#include "test_paths.h"

namespace shadowlab {
namespace provenance_test {

using Args = std::vector<std::string>;

// The program is argv[0]'s last path component and the arguments are the rest, also for a
// command without arguments; with argc 0 (no argv[0] at all) there are neither.
TEST(Provenance, RunCommandIsTheProgramsNameAndItsArguments) {
  std::vector<std::string> saved = run_arguments();
  saved.insert(saved.begin(), run_program());
  char prog[] = "/opt/x/render", a1[] = "--technique", a2[] = "csm";
  char* with_args[] = {prog, a1, a2, nullptr};
  set_run_command(3, with_args);
  EXPECT_EQ(run_program(), "render");
  EXPECT_EQ(run_arguments(), (Args{"--technique", "csm"}));
  char bare[] = "metric";
  char* alone[] = {bare, nullptr};
  set_run_command(1, alone);
  EXPECT_EQ(run_program(), "metric");
  EXPECT_TRUE(run_arguments().empty());
  char* none[] = {nullptr};
  set_run_command(0, none);
  EXPECT_EQ(run_program(), "metric");  // unchanged: no name was given
  EXPECT_TRUE(run_arguments().empty());
  std::vector<char*> restore;
  for (std::string& a : saved) restore.push_back(a.data());
  set_run_command(int(restore.size()), restore.data());
}

// --from FILE takes --out DIR and --threads N beside it, each with its value: anything else, or
// one of them last without a value, is refused naming it.
TEST(Provenance, FromTakesOnlyOutAndThreadsWithTheirValues) {
  const std::string path = test::binary_path("provenance_from.json");
  std::ofstream(path) << R"({"provenance": {"program": "render", "command": ["--technique", "csm"]}})";
  EXPECT_EQ(arguments_from_run("render", path, {"--out", "o", "--threads", "2"}),
            (Args{"--technique", "csm", "--out", "o", "--threads", "2"}));
  for (const Args& bad : {Args{"--out"}, Args{"--threads", "2", "--out"}, Args{"--scene", "x"}}) {
    try {
      arguments_from_run("render", path, bad);
      ADD_FAILURE() << bad.back();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("only --out DIR and --threads N"), std::string::npos) << e.what();
    }
  }
}

// Recorded scene hashes are read where they are well formed; an entry that is no object or
// lacks its name is skipped, never an exception from the JSON library.
TEST(Provenance, FromSkipsMalformedSceneEntries) {
  const std::string path = test::binary_path("provenance_scenes.json");
  std::ofstream(path) << R"({"provenance": {"program": "render", "command": ["--technique", "csm"],
                             "scenes": [5, {"hash": "ab"}, {"name": 7, "hash": "cd"}, {"name": "x", "hash": "ef"}]}})";
  EXPECT_NO_THROW(arguments_from_run("render", path, {}));
}

TEST(Provenance, CommandWithoutDropsTheFlagsAndTheirValuesInBothSpellings) {
  const Args args{"sweep", "--out", "dir", "--scene", "default", "--shard=2/4", "--threads", "2"};
  EXPECT_EQ(command_without(args, {"--out", "--shard", "--threads"}), (Args{"sweep", "--scene", "default"}));
  EXPECT_EQ(command_without(args, {}), args);
  // A flag as the last word has no value to drop with it; a value equal to a flag name is a value.
  EXPECT_EQ(command_without(Args{"a", "--out"}, {"--out"}), (Args{"a", "--out"}));
  EXPECT_EQ(command_without(Args{"--scene", "--out", "b"}, {"--scene"}), (Args{"b"}));
}

}  // namespace provenance_test
}  // namespace shadowlab
