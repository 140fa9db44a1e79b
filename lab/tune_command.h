#pragma once
// tune's command line as data: its flags declared on a CommandLine and, after parsing, the
// TuneConfig and scenes they describe. programs/tune.cpp and the Python module (python/) read
// the same flags through it, so both accept and refuse the same input with the same message.
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "lab/cli.h"
#include "lab/tuner.h"

namespace shadowlab {

struct TuneCommand {
  CommonOptions common;
  TuneConfig config;
  std::vector<std::string> spaces;
  std::string suite, shard, weights, strategy = "auto", objective = "total";
  std::optional<int> spp, repeats, max_evals;
  bool quick = false, no_cache = false, references_only = false;
  std::vector<double> budgets_ms = {2, 4, 8, 16, 32}, budgets_bytes;
};

// Declares the common flags and tune's own on cl, bound to cmd.
void add_tune_flags(CommandLine& cl, TuneCommand& cmd);
// After parse_command_line: the weights, shard, --quick's defaults and the parameter spaces;
// fills cmd.config. Throws InputError naming the flag.
void finish_tune_command(TuneCommand& cmd);
// The scenes the command tunes over (the suite's, or the one --scene describes), each built and
// its inputs checked.
std::vector<Scene> tune_scenes(const TuneCommand& cmd);

}  // namespace shadowlab
