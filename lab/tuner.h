#pragma once
// The tuner behind programs/tune.cpp: evaluates points of parameter spaces (lab/param_space.h)
// against the ray-traced reference and finds, per time or bytes budget, the best
// configuration overall and per technique (docs/programs/tune.md).
//
// Evaluations are ordered: point-major over the spaces in the order given, then scene; each has
// an index in that list, which --shard i/N uses (index mod N == i). Strategy `grid` evaluates
// every point at the full image size; `halving` (successive halving) first evaluates every point
// at 1/small_divisor of the image size per axis against a small_spp reference ("rung 0"), keeps
// per technique the first layers of non-dominated points in (objective up, shadow time down)
// until at least 1/eta of them are kept, and evaluates those at the full size ("rung 1"). Only
// rung-1 evaluations enter the tables.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"
#include "lab/param_space.h"
#include "metric/shadow_metric.h"
#include "techniques/registry/technique.h"

namespace shadowlab {

struct TuneConfig {
  std::vector<ParamSpace> spaces;
  std::vector<double> budgets_ms;      // shadow time (map + lookup, median of repeats), ms
  std::vector<double> budgets_bytes;   // map bytes touched (written + read)
  std::string objective = "total";     // a MetricReport field, higher is better (tune_objectives)
  MetricWeights weights = {1.0, 1.0, 1.0, 0.0, 30.0};  // time enters through the budgets
  std::string strategy = "auto";       // grid, halving, or auto (grid up to kAutoGridPoints)
  size_t max_evals = 2000;             // grid: refuse more evaluations than this
  int spp = 256;                       // reference samples per pixel (rung 1)
  int repeats = 5;                     // timing repeats, the median kept
  std::string cache_dir;               // reference cache; empty: none
  int shard = 0, shards = 1;           // this process evaluates index mod shards == shard
  int eta = 3;                         // halving keeps at least 1/eta of each technique's points
  int small_divisor = 4;               // halving's rung 0: image size / this, per axis
  int small_spp = 64;                  // halving's rung 0 reference spp
  uint64_t max_memory = 0;             // as SweepConfig::max_memory
  bool progress = false;               // progress line on stderr
};

// The strategy `auto` picks grid for at most this many evaluations, else halving.
constexpr size_t kAutoGridPoints = 96;

// The objectives --objective accepts, each a MetricReport field where higher is better.
const std::vector<std::string>& tune_objectives();
double objective_value(const MetricReport& m, const std::string& objective);

struct TuneEval {
  size_t index = 0;          // in the ordered list of this rung's evaluations
  size_t point = 0;          // the point's index over all spaces
  int rung = 1;              // 0: halving's small rung; 1: full size
  std::string scene;
  std::string technique;     // registry name, e.g. "csm"
  std::string spec;          // canonical spec text
  int width = 0, height = 0, spp = 0;
  MetricReport report;
  double objective = 0.0;
  double faces_ms = 0, render_ms = 0, filter_ms = 0, map_ms = 0, lookup_ms = 0;
  WorkCounts work;
  double shadow_ms() const { return map_ms + lookup_ms; }
};

struct TuneResult {
  std::vector<std::string> scenes;
  std::vector<std::string> points;        // every point's spec as generated, in order
  std::string strategy;                   // the strategy that ran (grid or halving)
  std::vector<TuneEval> evals;            // in (rung, index) order
  size_t rung_total[2] = {0, 0};          // evaluations each rung has over all shards
};

// Halving's survivors of one technique's points (indices, ascending): the first layers of points
// non-dominated in (objective up, map bytes touched down; util/pareto_plot.h's
// pareto_front) until at least ceil(n / eta) are kept. Bytes, not time: work counts are the same
// on every run, so the selection is deterministic.
std::vector<size_t> halving_survivors(const std::vector<double>& objective,
                                      const std::vector<double>& bytes, int eta);

// Checks the spaces, objective and budgets against the scenes (every point's spec parsed and
// validated, the strategy's evaluation count, the memory) before any work; throws InputError.
void check_tune(const std::vector<Scene>& scenes, const TuneConfig& config);
TuneResult run_tune(const std::vector<Scene>& scenes, const TuneConfig& config);
// Computes (or finds cached) every reference the run would need, then returns: the first step
// of a sharded run, so that shards sharing the cache never compute one twice.
void tune_references(const std::vector<Scene>& scenes, const TuneConfig& config);

}  // namespace shadowlab
