// tune: the best technique and settings for a scene (or a suite) and a time or bytes budget,
// searched over parameter spaces (lab/param_space.h); --shard i/N evaluates one deterministic
// share, which build/programs/merge combines.
#include <cstdio>

#include "core/error.h"
#include "core/parallel.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/provenance.h"
#include "lab/tune_report.h"
#include "lab/tune_command.h"
#include "lab/tuner.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("tune", "[--space SPEC]... [--budget-ms LIST] [flags]");
    TuneCommand cmd;
    add_tune_flags(cl, cmd);
    if (!parse_command_line(cl, argc, argv)) return 0;
    finish_tune_command(cmd);
    const CommonOptions& common = cmd.common;
    const TuneConfig& c = cmd.config;
    const std::vector<Scene> scenes = tune_scenes(cmd);
    check_tune(scenes, c);  // every point, count and the memory, before any work
    if (cmd.references_only) {
      if (c.cache_dir.empty()) throw InputError("--references-only", "needs the reference cache (not with --no-cache)");
      tune_references(scenes, c);
      std::printf("references of %zu scene(s) in %s\n", scenes.size(), c.cache_dir.c_str());
      return 0;
    }
    // A shard adds its files to the folder the other shards write into.
    RunOutputs outputs(common.out, "--out", c.shards > 1);
    if (c.shards > 1) {
      const std::string stem = "tune_shard" + std::to_string(c.shard) + "of" + std::to_string(c.shards);
      outputs.check_names({stem + ".csv", stem + ".json"});
    } else {
      outputs.check_names({"tune.csv", "tune.json", "tune.svg"});
    }
    const TuneResult r = run_tune(scenes, c);
    std::vector<const Scene*> sp;
    for (const Scene& s : scenes) sp.push_back(&s);
    const nlohmann::json prov = provenance_json(sp, c.spp, c.repeats);
    if (c.shards > 1) {
      std::printf("shard %d/%d: %zu of %zu evaluations\n", c.shard, c.shards, r.evals.size(), r.rung_total[1]);
    } else {
      std::printf("%s", tune_table(r, c).c_str());
    }
    const std::string written = write_tune_outputs(outputs.dir(), r, c, prov);
    outputs.commit();
    std::printf("wrote %s/%s\n", common.out.c_str(), written.c_str());
    return 0;
  });
}
