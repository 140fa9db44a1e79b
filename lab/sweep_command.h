#pragma once
// resolution_sweep's command line as data: its flags declared on a CommandLine and, after
// parsing, the SweepConfig and scenes they describe. programs/resolution_sweep.cpp and the
// Python module (python/) read the same flags through it, so both accept and refuse the same
// input with the same message.
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "lab/cli.h"
#include "lab/sweep.h"

namespace shadowlab {

struct SweepCommand {
  CommonOptions common;
  SweepConfig config;
  std::string techniques = "csm";
  std::optional<int> spp, repeats;
  bool quick = false, no_cache = false;
  std::string plot;
  bool plot_given = false;
  std::string sheet = "mask";
  std::optional<double> ambient;
  std::string suite;                      // empty: one scene (--scene)
  std::vector<std::string> suite_scenes;  // the suite's scene names (finish_sweep_command)
  std::string shard;
};

// Declares the common flags and resolution_sweep's own on cl, bound to cmd.
void add_sweep_flags(CommandLine& cl, SweepCommand& cmd);
// After parse_command_line: the rules between flags (--suite against --scene, --plot and
// --shard; --sheet's words) and the defaults that depend on others (--quick's size, spp and
// repeats); fills cmd.config. Throws InputError naming the flag.
void finish_sweep_command(SweepCommand& cmd);
// The scenes the command runs: the suite's, or the one --scene describes, each built and its
// inputs checked (scene_from_options) before any sweep.
std::vector<Scene> sweep_scenes(const SweepCommand& cmd);
// One scene's files in `dir`: sweep.csv, sweep.json, contact_sheet.png (masks or shaded, as
// config says) and, when `plot_file` is not empty, the score-against-time SVG there.
void write_sweep_files(const std::string& dir, const SweepResult& r, const SweepConfig& config,
                       const std::string& plot_file = "");

}  // namespace shadowlab
