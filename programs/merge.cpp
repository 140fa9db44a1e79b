// merge: combines the shard files of `tune --shard i/N` (tune_shardIofN.json) or
// `resolution_sweep --shard i/N` (sweep_shardIofN.json) into the tables, CSV, JSON and plot of
// one unsharded run, after checking that every evaluation or row is present exactly once and
// that the shards share their configuration and provenance.
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/run_inputs.h"
#include "lab/cli.h"
#include "core/json_file.h"
#include "util/json_read.h"
#include "lab/output_folder.h"
#include "lab/provenance.h"
#include "lab/sweep.h"
#include "lab/tune_report.h"

using namespace shadowlab;

namespace {

// The merged provenance: shard 0's, with the command that repeats the whole run (--from): the
// shard's command without --shard and --out.
nlohmann::json merged_provenance(const nlohmann::json& shard0, const std::vector<std::string>& paths) {
  nlohmann::json prov = shard0;
  const std::vector<std::string> cmd = command_without(json_strings(shard0, "command", paths[0]), {"--shard", "--out"});
  prov["command"] = cmd;
  prov["merged_from"] = paths;
  prov["merged_by"] = provenance_json({}, 0, 0);
  return prov;
}

// Writes into `dir` (the staging folder); `out` is --out, as printed.
int merge(const std::vector<nlohmann::json>& shards, const std::vector<std::string>& paths,
          const std::string& dir, const std::string& out) {
    if (shards[0].contains("kind") && shards[0]["kind"] == "sweep") {
      SweepResult r = merge_sweep_shards(shards, paths);
      r.provenance = merged_provenance(r.provenance, paths);
      std::printf("%s", sweep_table(r).c_str());
      write_sweep_csv(dir + "/sweep.csv", r);
      write_sweep_json(dir + "/sweep.json", r);
      write_pareto_svg(dir + "/plot.svg", sweep_plot_points(r),
                       "resolution_sweep: " + r.scene + ", " + std::to_string(r.width) + "x" +
                           std::to_string(r.height) + " (merged from " + std::to_string(shards.size()) + " shards)");
      std::printf("merged %zu shards; wrote %s/sweep.csv, sweep.json, plot.svg\n", shards.size(), out.c_str());
      return 0;
    }
    const TuneResult r = merge_tune_shards(shards, paths);
    TuneConfig c = tune_config_from_json(json_at(shards[0], "config", paths[0]), paths[0]);
    c.shards = 1;
    c.shard = 0;
    const nlohmann::json prov = merged_provenance(json_at(shards[0], "provenance", paths[0]), paths);
    std::printf("%s", tune_table(r, c).c_str());
    std::printf("merged %zu shards; wrote %s/%s\n", shards.size(), out.c_str(),
                write_tune_outputs(dir, r, c, prov).c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("merge", "SHARD.json... [--out DIR]  (tune_shardIofN.json or sweep_shardIofN.json files)");
    std::string out = "out/merge";
    add_text(cl, "--out", "DIR", "output folder (default out/merge)", out);
    if (!parse_command_line(cl, argc, argv, 100000)) return 0;
    const std::vector<std::string>& paths = cl.positional;
    if (paths.empty()) throw InputError("merge", "give the shard files (tune_shardIofN.json)");
    std::vector<nlohmann::json> shards;
    for (const std::string& p : paths) {
      note_input(p);
      nlohmann::json j = read_json_file(p, kResultFileLimit);
      if (!j.is_object()) throw InputError(p, "not a JSON object");
      shards.push_back(std::move(j));
    }
    // Added to the folder's set: the shards are often in it.
    RunOutputs outputs(out, "--out", true);
    if (shards[0].contains("kind") && shards[0]["kind"] == "sweep")
      outputs.check_names({"sweep.csv", "sweep.json", "plot.svg"});
    else
      outputs.check_names({"tune.csv", "tune.json", "tune.svg"});
    try {
      const int code = merge(shards, paths, outputs.dir(), out);
      outputs.commit();
      return code;
    } catch (const nlohmann::json::exception& e) {
      // A field of the wrong type in a shard file (the readers check what they convert).
      throw InputError("merge", "malformed shard file: " + json_error_text(e));
    }
  });
}
