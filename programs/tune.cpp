// tune: the best technique and settings for a scene (or a suite) and a time or bytes budget,
// searched over parameter spaces (lab/param_space.h); --shard i/N evaluates one deterministic
// share, which build/programs/merge combines.
#include <cstdio>

#include "core/error.h"
#include "core/parallel.h"
#include "core/parse_number.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/provenance.h"
#include "lab/tune_report.h"
#include "lab/tuner.h"
#include "raytrace/reference_cache.h"
#include "scenes/scene_registry.h"

using namespace shadowlab;

namespace {

void parse_weights(const std::string& s, MetricWeights& w) {
  for (const std::string& item : split_spec_list("w:" + s)) {
    const Spec spec = parse_spec(item, "--metric-weights");
    SpecReader r(spec, "--metric-weights");
    w.fidelity = r.get_double("fidelity", w.fidelity, 0.0, 1e6);
    w.aesthetics = r.get_double("aesthetics", w.aesthetics, 0.0, 1e6);
    w.detail = r.get_double("detail", w.detail, 0.0, 1e6);
    w.performance = r.get_double("performance", w.performance, 0.0, 1e6);
    r.reject_unknown();
  }
  if (!(w.fidelity + w.aesthetics + w.detail + w.performance > 0.0))
    throw InputError("--metric-weights", "every weight is 0");
}

}  // namespace

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("tune", "[--space SPEC]... [--budget-ms LIST] [flags]");
    CommonOptions common;
    add_common_options(cl, common);
    TuneConfig c;
    std::vector<std::string> spaces;
    std::string suite, shard, weights, strategy = "auto", objective = "total";
    std::optional<int> spp, repeats, max_evals;
    bool quick = false, no_cache = false, references_only = false;
    std::vector<double> budgets_ms = {2, 4, 8, 16, 32}, budgets_bytes;
    add_text_repeated(cl, "--space", "SPEC", "a technique's parameter space, e.g. csm:res=256..2048/x2,pcf=1|3|5 (repeatable; default: the spaces of --list-keys' last section)", spaces);
    add_double_list(cl, "--budget-ms", "LIST", "shadow-time budgets in ms (default 2,4,8,16,32)", budgets_ms, 1e-6, 1e9);
    add_double_list(cl, "--budget-bytes", "LIST", "map-bytes-touched budgets in bytes, e.g. 4e6,16e6 (default: none)", budgets_bytes, 1.0, 1e18);
    add_text(cl, "--objective", "NAME", "what to maximize: total, fidelity, aesthetics, detail, ssim, psnr, c10, c50, c90, dark, lit, acne, noise or flip (1 - mean FLIP of the masks) (default total)", objective);
    add_text(cl, "--metric-weights", "LIST", "weights of the total, e.g. fidelity=1,aesthetics=1,detail=1,performance=0 (default: those; time enters through the budgets)", weights);
    add_text(cl, "--strategy", "S", "grid (every point at full size), halving (successive halving) or auto (grid up to 96 evaluations) (default auto)", strategy);
    add_int(cl, "--max-evals", "N", "refuse a search costing more full-size evaluations than N (default 2000)", max_evals, 1, 100000000);
    add_int(cl, "--spp", "N", "reference samples per pixel (default 256)", spp, 1, 1 << 20);
    add_int(cl, "--repeats", "N", "timed runs per evaluation, the median kept (default 5; 3 with --quick)", repeats, 1, 100000);
    add_switch(cl, "--quick", "CI size: 320x240, 64 spp, 3 repeats (explicit flags still win)", quick);
    add_switch(cl, "--no-cache", "do not read or write the reference cache", no_cache);
    add_text(cl, "--suite", "NAME", "tune over every scene of a suite (hard, all) instead of --scene: the mean objective, the largest time and bytes (default: none)", suite);
    add_text(cl, "--shard", "i/N", "evaluate only evaluations with index mod N == i (grid only); combine with build/programs/merge (default 0/1)", shard);
    add_switch(cl, "--references-only", "compute (or find cached) the references the run needs, then exit: the first step of a sharded run", references_only);
    if (!parse_command_line(cl, argc, argv)) return 0;
    c.budgets_ms = budgets_ms;
    c.budgets_bytes = budgets_bytes;
    c.objective = objective;
    c.strategy = strategy;
    if (!weights.empty()) parse_weights(weights, c.weights);
    if (max_evals) c.max_evals = size_t(*max_evals);
    if (!shard.empty()) parse_shard(shard, c.shard, c.shards);
    if (quick) {
      if (!common.width) common.width = 320;
      if (!common.height) common.height = 240;
    }
    c.spp = spp.value_or(quick ? 64 : 256);
    c.small_spp = std::min(c.small_spp, c.spp);
    c.repeats = repeats.value_or(quick ? 3 : 5);
    c.cache_dir = no_cache ? "" : default_cache_dir();
    c.progress = stderr_is_terminal();
    c.max_memory = max_memory_bytes(common);
    for (const std::string& s : spaces.empty() ? default_param_spaces() : spaces)
      c.spaces.push_back(parse_param_space(s, "--space"));
    std::vector<Scene> scenes;
    if (!suite.empty()) {
      reject_scene_with_suite(common);
      for (const std::string& name : scene_suite(suite, "--suite")) {
        CommonOptions o = common;
        o.scene = name;
        scenes.push_back(scene_from_options(o));
      }
    } else {
      scenes.push_back(scene_from_options(common));
    }
    check_tune(scenes, c);  // every point, count and the memory, before any work
    if (references_only) {
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
