#pragma once
// What the tuner reports (docs/programs/tune.md): per budget the best configuration overall and per
// technique, the Pareto fronts of objective against time and against bytes, every evaluation as
// CSV and JSON, and the plot with the chosen points marked. Also reads the JSON back, which is
// how shards are merged: the merged report is computed by the same functions from the same
// numbers, so it equals an unsharded run's.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "util/pareto_plot.h"
#include "lab/tuner.h"

namespace shadowlab {

// One point's rung-1 result over every scene: the mean objective (scenes in order), the largest
// shadow time and bytes (a budget must hold on every scene).
struct TuneSummary {
  size_t point = 0;
  std::string technique, spec;
  double objective = 0.0;
  double time_ms = 0.0;
  double bytes = 0.0;
};
// Needs every rung-1 evaluation (an unsharded or merged result); throws otherwise.
std::vector<TuneSummary> tune_summaries(const TuneResult& r);

// The best summary under a budget (cost <= budget): highest objective, then lowest cost, then
// lowest point index; nullptr when none fits. technique empty: over every technique.
const TuneSummary* best_under(const std::vector<TuneSummary>& s, double budget, bool bytes,
                              const std::string& technique = "");

// The MetricReport and WorkCounts fields of an evaluation, in tune.csv's column order.
std::vector<std::pair<const char*, double MetricReport::*>> tune_report_fields();
std::vector<std::pair<const char*, uint64_t WorkCounts::*>> tune_work_fields();

// The printed report: evaluations per rung, a table per budget kind (budget → best overall,
// then the best of each technique), and both Pareto fronts.
std::string tune_table(const TuneResult& r, const TuneConfig& c);

// Every evaluation (both rungs); `provenance` is written as the CSV's first line
// ("# provenance {...}") and the JSON's "provenance" member.
void write_tune_csv(const std::string& path, const TuneResult& r, const nlohmann::json& provenance);
nlohmann::json tune_json(const TuneResult& r, const TuneConfig& c, const nlohmann::json& provenance);
// The config fields that must agree between shards (all of tune_json's "config" but the shard).
nlohmann::json tune_config_json(const TuneConfig& c);
// Reads tune_json's output back (evaluations, points, scenes, rung totals); `where` names the
// file in errors.
TuneResult tune_from_json(const nlohmann::json& j, const std::string& where);

// Plot points: every rung-1 summary, series = technique; the budget winners marked.
std::vector<PlotPoint> tune_plot_points(const TuneResult& r, const TuneConfig& c);

// Combines shard results: the same config (but the shard), scenes, points and rung totals in
// every shard, and every evaluation index present exactly once; throws InputError naming the
// file otherwise.
TuneResult merge_tune_shards(const std::vector<nlohmann::json>& shards,
                             const std::vector<std::string>& paths);

}  // namespace shadowlab

namespace shadowlab {
// The config tune_config_json wrote (spaces re-parsed), for reports of merged shards.
TuneConfig tune_config_from_json(const nlohmann::json& j, const std::string& where);
// Writes tune.csv, tune.json and tune.svg (or, for one shard of several, tune_shardIofN.csv and
// .json only) into dir; returns the file names written.
std::string write_tune_outputs(const std::string& dir, const TuneResult& r, const TuneConfig& c,
                               const nlohmann::json& provenance);
}  // namespace shadowlab
