#include "lab/tune_command.h"

#include <algorithm>

#include "core/error.h"
#include "core/spec.h"
#include "raytrace/reference_cache.h"
#include "scenes/scene_registry.h"

namespace shadowlab {

namespace {

void parse_tune_weights(const std::string& s, MetricWeights& w) {
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

void add_tune_flags(CommandLine& cl, TuneCommand& cmd) {
  add_common_options(cl, cmd.common);
  add_text_repeated(cl, "--space", "SPEC", "a technique's parameter space, e.g. csm:res=256..2048/x2,pcf=1|3|5 (repeatable; default: the spaces of --list-keys' last section)", cmd.spaces);
  add_double_list(cl, "--budget-ms", "LIST", "shadow-time budgets in ms (default 2,4,8,16,32)", cmd.budgets_ms, 1e-6, 1e9);
  add_double_list(cl, "--budget-bytes", "LIST", "map-bytes-touched budgets in bytes, e.g. 4e6,16e6 (default: none)", cmd.budgets_bytes, 1.0, 1e18);
  add_text(cl, "--objective", "NAME", "what to maximize: total, fidelity, aesthetics, detail, ssim, psnr, c10, c50, c90, dark, lit, acne, noise or flip (1 - mean FLIP of the masks) (default total)", cmd.objective);
  add_text(cl, "--metric-weights", "LIST", "weights of the total, e.g. fidelity=1,aesthetics=1,detail=1,performance=0 (default: those; time enters through the budgets)", cmd.weights);
  add_text(cl, "--strategy", "S", "grid (every point at full size), halving (successive halving) or auto (grid up to 96 evaluations) (default auto)", cmd.strategy);
  add_int(cl, "--max-evals", "N", "refuse a search costing more full-size evaluations than N (default 2000)", cmd.max_evals, 1, 100000000);
  add_int(cl, "--spp", "N", "reference samples per pixel (default 256)", cmd.spp, 1, 1 << 20);
  add_int(cl, "--repeats", "N", "timed runs per evaluation, the median kept (default 5; 3 with --quick)", cmd.repeats, 1, 100000);
  add_switch(cl, "--quick", "CI size: 320x240, 64 spp, 3 repeats (explicit flags still win)", cmd.quick);
  add_switch(cl, "--no-cache", "do not read or write the reference cache", cmd.no_cache);
  add_text(cl, "--suite", "NAME", "tune over every scene of a suite (hard, all) instead of --scene: the mean objective, the largest time and bytes (default: none)", cmd.suite);
  add_text(cl, "--shard", "i/N", "evaluate only evaluations with index mod N == i (grid only); combine with build/programs/merge (default 0/1)", cmd.shard);
  add_switch(cl, "--references-only", "compute (or find cached) the references the run needs, then exit: the first step of a sharded run", cmd.references_only);
}

void finish_tune_command(TuneCommand& cmd) {
  TuneConfig& c = cmd.config;
  CommonOptions& common = cmd.common;
  c.budgets_ms = cmd.budgets_ms;
  c.budgets_bytes = cmd.budgets_bytes;
  c.objective = cmd.objective;
  c.strategy = cmd.strategy;
  if (!cmd.weights.empty()) parse_tune_weights(cmd.weights, c.weights);
  if (cmd.max_evals) c.max_evals = size_t(*cmd.max_evals);
  if (!cmd.shard.empty()) parse_shard(cmd.shard, c.shard, c.shards);
  if (cmd.quick) {
    if (!common.width) common.width = 320;
    if (!common.height) common.height = 240;
  }
  c.spp = cmd.spp.value_or(cmd.quick ? 64 : 256);
  c.small_spp = std::min(c.small_spp, c.spp);
  c.repeats = cmd.repeats.value_or(cmd.quick ? 3 : 5);
  c.cache_dir = cmd.no_cache ? "" : default_cache_dir();
  c.progress = stderr_is_terminal();
  c.max_memory = max_memory_bytes(common);
  for (const std::string& s : cmd.spaces.empty() ? default_param_spaces() : cmd.spaces)
    c.spaces.push_back(parse_param_space(s, "--space"));
}

std::vector<Scene> tune_scenes(const TuneCommand& cmd) {
  std::vector<Scene> scenes;
  if (!cmd.suite.empty()) {
    reject_scene_with_suite(cmd.common);
    for (const std::string& name : scene_suite(cmd.suite, "--suite")) {
      CommonOptions o = cmd.common;
      o.scene = name;
      scenes.push_back(scene_from_options(o));
    }
  } else {
    scenes.push_back(scene_from_options(cmd.common));
  }
  return scenes;
}

}  // namespace shadowlab
