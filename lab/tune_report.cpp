#include "lab/tune_report.h"

#include <cmath>
#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "core/output_file.h"
#include "util/json_read.h"
#include "lab/output_files.h"

namespace shadowlab {
namespace {

// Indices and counts read back are at most this (a tune never has more evaluations).
constexpr uint64_t kMaxIndex = uint64_t(1) << 40;

nlohmann::json eval_json(const TuneEval& e) {
  nlohmann::json j;
  j["index"] = e.index;
  j["point"] = e.point;
  j["rung"] = e.rung;
  j["scene"] = e.scene;
  j["technique"] = e.technique;
  j["spec"] = e.spec;
  j["width"] = e.width;
  j["height"] = e.height;
  j["spp"] = e.spp;
  j["objective"] = e.objective;
  for (const auto& [k, m] : tune_report_fields()) j[k] = e.report.*m;
  j["has_performance"] = e.report.has_performance;
  j["faces_ms"] = e.faces_ms;
  j["render_ms"] = e.render_ms;
  j["filter_ms"] = e.filter_ms;
  j["map_ms"] = e.map_ms;
  j["lookup_ms"] = e.lookup_ms;
  j["shadow_ms"] = e.shadow_ms();
  for (const auto& [k, m] : tune_work_fields()) j["work"][k] = e.work.*m;
  return j;
}

TuneEval eval_from_json(const nlohmann::json& j, const std::string& where) {
  TuneEval e;
  e.index = json_uint(j, "index", kMaxIndex, where);
  e.point = json_uint(j, "point", kMaxIndex, where);
  e.rung = int(json_uint(j, "rung", 1, where));
  e.scene = json_string(j, "scene", where);
  e.technique = json_string(j, "technique", where);
  e.spec = json_string(j, "spec", where);
  e.width = int(json_uint(j, "width", 1 << 20, where));
  e.height = int(json_uint(j, "height", 1 << 20, where));
  e.spp = int(json_uint(j, "spp", 1 << 30, where));
  e.objective = json_number(j, "objective", where);
  // A file written before FLIP joined the metric has no flip_mean (NaN: not measured).
  for (const auto& [k, m] : tune_report_fields())
    e.report.*m = std::string(k) == "flip_mean" && !j.contains(k) ? std::nan("")
                                                                  : json_number(j, k, where);
  e.report.has_performance = json_bool(j, "has_performance", where);
  e.faces_ms = json_number(j, "faces_ms", where);
  e.render_ms = json_number(j, "render_ms", where);
  e.filter_ms = json_number(j, "filter_ms", where);
  e.map_ms = json_number(j, "map_ms", where);
  e.lookup_ms = json_number(j, "lookup_ms", where);
  for (const auto& [k, m] : tune_work_fields()) e.work.*m = json_uint(json_at(j, "work", where), k, UINT64_MAX, where);
  return e;
}

std::string mb_text(double bytes) { return fmt::format("{:.1f} MB", bytes * 1e-6); }

// Budget values as given: "4 ms", "16.5 MB".
std::string budget_text(double b, bool bytes) {
  return bytes ? fmt::format("{:g} MB", b * 1e-6) : fmt::format("{:g} ms", b);
}

}  // namespace

std::vector<std::pair<const char*, double MetricReport::*>> tune_report_fields() {
  return {{"c10", &MetricReport::c10},       {"c50", &MetricReport::c50},
          {"c90", &MetricReport::c90},       {"dark", &MetricReport::dark},
          {"lit", &MetricReport::lit},       {"acne", &MetricReport::acne},
          {"noise", &MetricReport::noise},   {"detail", &MetricReport::detail},
          {"fidelity", &MetricReport::fidelity}, {"aesthetics", &MetricReport::aesthetics},
          {"performance", &MetricReport::performance}, {"total", &MetricReport::total},
          {"ssim", &MetricReport::ssim},     {"rmse", &MetricReport::rmse},
          {"psnr", &MetricReport::psnr},     {"flip_mean", &MetricReport::flip_mean}};
}

std::vector<std::pair<const char*, uint64_t WorkCounts::*>> tune_work_fields() {
  return {{"triangles_submitted", &WorkCounts::triangles_submitted},
          {"triangles_binned", &WorkCounts::triangles_binned},
          {"texels_rendered", &WorkCounts::texels_rendered},
          {"texels_filtered", &WorkCounts::texels_filtered},
          {"pixels_looked_up", &WorkCounts::pixels_looked_up},
          {"taps", &WorkCounts::taps},
          {"bytes_written", &WorkCounts::bytes_written},
          {"bytes_read", &WorkCounts::bytes_read}};
}


std::vector<TuneSummary> tune_summaries(const TuneResult& r) {
  const size_t n_scenes = r.scenes.size();
  std::map<size_t, std::vector<const TuneEval*>> by_point;
  size_t rung1 = 0;
  for (const TuneEval& e : r.evals)
    if (e.rung == 1) {
      by_point[e.point].push_back(&e);
      ++rung1;
    }
  if (rung1 != r.rung_total[1])
    throw InputError("tune", fmt::format("{} of {} full-size evaluations present (a shard's result: merge the shards first)",
                                         rung1, r.rung_total[1]));
  std::vector<TuneSummary> out;
  for (const auto& [point, evals] : by_point) {
    TuneSummary s;
    s.point = point;
    s.technique = evals.front()->technique;
    s.spec = evals.front()->spec;
    // evals are in index order, so in scene order within a point: a fixed order of additions.
    for (const TuneEval* e : evals) {
      s.objective += e->objective / double(n_scenes);
      s.time_ms = std::max(s.time_ms, e->shadow_ms());
      s.bytes = std::max(s.bytes, double(e->work.bytes_touched()));
    }
    out.push_back(s);
  }
  return out;
}

const TuneSummary* best_under(const std::vector<TuneSummary>& s, double budget, bool bytes,
                              const std::string& technique) {
  const TuneSummary* best = nullptr;
  for (const TuneSummary& x : s) {
    if (!technique.empty() && x.technique != technique) continue;
    const double cost = bytes ? x.bytes : x.time_ms;
    if (!(cost <= budget) || !std::isfinite(x.objective)) continue;
    const double best_cost = best ? (bytes ? best->bytes : best->time_ms) : 0.0;
    if (!best || x.objective > best->objective ||
        (x.objective == best->objective && (cost < best_cost || (cost == best_cost && x.point < best->point))))
      best = &x;
  }
  return best;
}

std::string tune_table(const TuneResult& r, const TuneConfig& c) {
  const std::vector<TuneSummary> sums = tune_summaries(r);
  std::vector<std::string> techniques;
  for (const TuneSummary& s : sums)
    if (std::find(techniques.begin(), techniques.end(), s.technique) == techniques.end())
      techniques.push_back(s.technique);
  std::string out;
  std::string scenes;
  for (const std::string& s : r.scenes) scenes += (scenes.empty() ? "" : ", ") + s;
  if (r.strategy == "halving") {
    out += fmt::format("successive halving: rung 0 ran {} evaluations at 1/{} of the image size per axis, {} spp; "
                       "rung 1 ran {} at full size, {} spp\n",
                       r.rung_total[0], c.small_divisor, c.small_spp, r.rung_total[1], c.spp);
  } else {
    out += fmt::format("grid: {} evaluations at full size, {} spp\n", r.rung_total[1], c.spp);
  }
  out += fmt::format("{} points over {} scene(s) ({}); objective {}{}\n", r.points.size(),
                     r.scenes.size(), scenes, c.objective,
                     r.scenes.size() > 1 ? " (mean over the scenes; time and bytes: the largest)" : "");
  auto table = [&](const std::vector<double>& budgets, bool bytes) {
    if (budgets.empty()) return;
    out += fmt::format("\n{:<10} {:<10} {:<44} {:>9} {:>9} {:>10}\n", "budget",
                       "technique", "settings", c.objective, "time ms", "MB");
    for (double b : budgets) {
      const TuneSummary* best = best_under(sums, b, bytes);
      const std::string bt = budget_text(b, bytes);
      if (!best) {
        out += fmt::format("{:<10} (nothing fits)\n", bt);
        continue;
      }
      auto row = [&](const std::string& first, const TuneSummary& s, const char* mark) {
        out += fmt::format("{:<10} {:<10} {:<44} {:>9.4f} {:>9.2f} {:>10.1f}{}\n", first, s.technique,
                           s.spec, s.objective, s.time_ms, s.bytes * 1e-6, mark);
      };
      row(bt, *best, "  <- best");
      for (const std::string& t : techniques) {
        const TuneSummary* bt_best = best_under(sums, b, bytes, t);
        if (bt_best && bt_best != best) row("", *bt_best, "");
      }
    }
  };
  table(c.budgets_ms, false);
  table(c.budgets_bytes, true);
  auto front = [&](bool bytes) {
    std::vector<double> cost, score;
    for (const TuneSummary& s : sums) {
      cost.push_back(bytes ? s.bytes : s.time_ms);
      score.push_back(s.objective);
    }
    const std::vector<bool> f = pareto_front(cost, score);
    std::vector<size_t> order;
    for (size_t i = 0; i < sums.size(); ++i)
      if (f[i]) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return cost[a] != cost[b] ? cost[a] < cost[b] : sums[a].point < sums[b].point;
    });
    out += fmt::format("\nPareto front, {} against {}:\n", c.objective, bytes ? "map bytes touched" : "shadow time");
    for (size_t i : order)
      out += fmt::format("  {:>10} {:<44} {:.4f}\n",
                         bytes ? mb_text(sums[i].bytes) : fmt::format("{:.2f} ms", sums[i].time_ms),
                         sums[i].spec, sums[i].objective);
  };
  front(false);
  front(true);
  return out;
}

void write_tune_csv(const std::string& path, const TuneResult& r, const nlohmann::json& provenance) {
  std::string s = "# provenance " + provenance.dump() + "\n";
  s += "index,rung,point,scene,technique,spec,width,height,spp,objective";
  for (const auto& [k, m] : tune_report_fields()) s += std::string(",") + k;
  s += ",faces_ms,render_ms,filter_ms,map_ms,lookup_ms,shadow_ms";
  for (const auto& [k, m] : tune_work_fields()) s += std::string(",") + k;
  s += "\n";
  for (const TuneEval& e : r.evals) {
    s += fmt::format("{},{},{},{},{},\"{}\",{},{},{},{}", e.index, e.rung, e.point, e.scene,
                     e.technique, e.spec, e.width, e.height, e.spp, e.objective);
    for (const auto& [k, m] : tune_report_fields()) s += fmt::format(",{}", e.report.*m);
    s += fmt::format(",{},{},{},{},{},{}", e.faces_ms, e.render_ms, e.filter_ms, e.map_ms,
                     e.lookup_ms, e.shadow_ms());
    for (const auto& [k, m] : tune_work_fields()) s += fmt::format(",{}", e.work.*m);
    s += "\n";
  }
  write_text_file(path, s);
}

nlohmann::json tune_config_json(const TuneConfig& c) {
  nlohmann::json j;
  j["spaces"] = nlohmann::json::array();
  for (const ParamSpace& s : c.spaces) j["spaces"].push_back(s.text);
  j["budgets_ms"] = c.budgets_ms;
  j["budgets_bytes"] = c.budgets_bytes;
  j["objective"] = c.objective;
  j["weights"] = {{"fidelity", c.weights.fidelity}, {"aesthetics", c.weights.aesthetics},
                  {"detail", c.weights.detail}, {"performance", c.weights.performance},
                  {"target_fps", c.weights.target_fps}};
  j["strategy"] = c.strategy;
  j["max_evals"] = c.max_evals;
  j["spp"] = c.spp;
  j["repeats"] = c.repeats;
  j["eta"] = c.eta;
  j["small_divisor"] = c.small_divisor;
  j["small_spp"] = c.small_spp;
  j["shards"] = c.shards;
  return j;
}

nlohmann::json tune_json(const TuneResult& r, const TuneConfig& c, const nlohmann::json& provenance) {
  nlohmann::json j;
  j["kind"] = "tune";
  j["provenance"] = provenance;
  j["config"] = tune_config_json(c);
  j["shard"] = c.shard;
  j["scenes"] = r.scenes;
  j["points"] = r.points;
  j["strategy"] = r.strategy;
  j["rung_total"] = {r.rung_total[0], r.rung_total[1]};
  j["evaluations"] = nlohmann::json::array();
  for (const TuneEval& e : r.evals) j["evaluations"].push_back(eval_json(e));
  return j;
}

TuneResult tune_from_json(const nlohmann::json& j, const std::string& where) {
  try {
    if (json_string(j, "kind", where) != "tune") throw InputError(where, "not a tune result (kind is not \"tune\")");
    TuneResult r;
    r.scenes = json_strings(j, "scenes", where);
    r.points = json_strings(j, "points", where);
    r.strategy = json_string(j, "strategy", where);
    const nlohmann::json& rungs = json_array(j, "rung_total", where);
    if (rungs.size() != 2) throw InputError(where, "'rung_total' is not a list of 2 counts");
    const nlohmann::json totals = {{"rung0", rungs[0]}, {"rung1", rungs[1]}};
    r.rung_total[0] = json_uint(totals, "rung0", kMaxIndex, where);
    r.rung_total[1] = json_uint(totals, "rung1", kMaxIndex, where);
    for (const nlohmann::json& e : json_array(j, "evaluations", where)) r.evals.push_back(eval_from_json(e, where));
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, "malformed tune result: " + json_error_text(e));
  }
}

std::vector<PlotPoint> tune_plot_points(const TuneResult& r, const TuneConfig& c) {
  const std::vector<TuneSummary> sums = tune_summaries(r);
  std::set<const TuneSummary*> chosen;
  for (double b : c.budgets_ms)
    if (const TuneSummary* s = best_under(sums, b, false)) chosen.insert(s);
  for (double b : c.budgets_bytes)
    if (const TuneSummary* s = best_under(sums, b, true)) chosen.insert(s);
  // Fidelity panel: the scenes' mean fidelity of the same evaluations.
  std::map<size_t, double> fidelity;
  for (const TuneEval& e : r.evals)
    if (e.rung == 1) fidelity[e.point] += e.report.fidelity / double(r.scenes.size());
  std::vector<PlotPoint> out;
  for (const TuneSummary& s : sums) {
    PlotPoint p;
    p.label = s.spec;
    p.series = s.technique;
    p.time_ms = s.time_ms;
    p.total = s.objective;
    p.fidelity = fidelity[s.point];
    p.bytes = s.bytes;
    p.chosen = chosen.count(&s) > 0;
    out.push_back(p);
  }
  return out;
}

TuneResult merge_tune_shards(const std::vector<nlohmann::json>& shards,
                             const std::vector<std::string>& paths) {
  if (shards.empty()) throw InputError("merge", "no shard files given");
  TuneResult merged = tune_from_json(shards[0], paths[0]);
  merged.evals.clear();
  const nlohmann::json& config0 = json_at(shards[0], "config", paths[0]);
  const int n = int(json_uint(config0, "shards", 100000, paths[0]));
  if (int(shards.size()) != n)
    throw InputError(paths[0], fmt::format("is one of {} shards, {} files given", n, shards.size()));
  // Provenance that must agree: what determines the scores. Machine and date may differ.
  auto must_agree = [](const nlohmann::json& p) {
    nlohmann::json k = p;
    for (const char* f : {"date", "cpu", "hostname", "command", "threads"}) k.erase(f);
    return k;
  };
  const nlohmann::json prov0 = must_agree(json_at(shards[0], "provenance", paths[0]));
  std::set<int> shard_ids;
  std::vector<int> seen_count;
  for (size_t i = 0; i < shards.size(); ++i) {
    const nlohmann::json& j = shards[i];
    TuneResult r = tune_from_json(j, paths[i]);
    if (json_at(j, "config", paths[i]) != config0)
      throw InputError(paths[i], "was run with a different configuration than " + paths[0]);
    const nlohmann::json prov = must_agree(json_at(j, "provenance", paths[i]));
    if (prov != prov0) throw InputError(paths[i], provenance_difference(prov, prov0, paths[0]));
    if (r.scenes != merged.scenes || r.points != merged.points || r.strategy != merged.strategy ||
        r.rung_total[0] != merged.rung_total[0] || r.rung_total[1] != merged.rung_total[1])
      throw InputError(paths[i], "lists other scenes, points or evaluation counts than " + paths[0]);
    const int id = int(json_uint(j, "shard", uint64_t(n - 1), paths[i]));  // n >= 1: the count matched
    if (!shard_ids.insert(id).second)
      throw InputError(paths[i], fmt::format("shard {} given twice", id));
    for (TuneEval& e : r.evals) {
      if (e.rung != 1 || e.index >= merged.rung_total[1] || int(e.index % size_t(n)) != id)
        throw InputError(paths[i], fmt::format("evaluation {} does not belong to shard {}/{}", e.index, id, n));
      merged.evals.push_back(std::move(e));
    }
  }
  std::sort(merged.evals.begin(), merged.evals.end(),
            [](const TuneEval& a, const TuneEval& b) { return a.index < b.index; });
  for (size_t k = 0; k < merged.evals.size(); ++k)
    if (merged.evals[k].index != k)
      throw InputError("merge", fmt::format("evaluation {} is {}", k,
                                            merged.evals[k].index < k ? "present twice" : "missing"));
  if (merged.evals.size() != merged.rung_total[1])
    throw InputError("merge", fmt::format("{} of {} evaluations present", merged.evals.size(), merged.rung_total[1]));
  return merged;
}

}  // namespace shadowlab

namespace shadowlab {

TuneConfig tune_config_from_json(const nlohmann::json& j, const std::string& where) {
  try {
    TuneConfig c;
    for (const std::string& s : json_strings(j, "spaces", where)) c.spaces.push_back(parse_param_space(s, where));
    for (const char* key : {"budgets_ms", "budgets_bytes"})
      for (const nlohmann::json& b : json_array(j, key, where)) {
        if (!b.is_number()) throw InputError(where, std::string("'") + key + "' is not a list of numbers");
        (std::string(key) == "budgets_ms" ? c.budgets_ms : c.budgets_bytes).push_back(b.get<double>());
      }
    c.objective = json_string(j, "objective", where);
    const nlohmann::json& w = json_at(j, "weights", where);
    c.weights.fidelity = json_number(w, "fidelity", where);
    c.weights.aesthetics = json_number(w, "aesthetics", where);
    c.weights.detail = json_number(w, "detail", where);
    c.weights.performance = json_number(w, "performance", where);
    c.weights.target_fps = json_number(w, "target_fps", where);
    c.strategy = json_string(j, "strategy", where);
    c.max_evals = json_uint(j, "max_evals", 100000000, where);
    c.spp = int(json_uint(j, "spp", 1 << 20, where));
    c.repeats = int(json_uint(j, "repeats", 100000, where));
    c.eta = int(std::max<uint64_t>(1, json_uint(j, "eta", 1000, where)));
    c.small_divisor = int(std::max<uint64_t>(1, json_uint(j, "small_divisor", 1000, where)));
    c.small_spp = int(json_uint(j, "small_spp", 1 << 20, where));
    c.shards = int(std::max<uint64_t>(1, json_uint(j, "shards", 100000, where)));
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, "malformed tune config: " + json_error_text(e));
  }
}

std::string write_tune_outputs(const std::string& dir, const TuneResult& r, const TuneConfig& c,
                               const nlohmann::json& provenance) {
  const std::string stem = c.shards > 1 ? fmt::format("tune_shard{}of{}", c.shard, c.shards) : "tune";
  write_tune_csv(dir + "/" + stem + ".csv", r, provenance);
  write_text_file(dir + "/" + stem + ".json", tune_json(r, c, provenance).dump(1) + "\n");
  if (c.shards > 1) return stem + ".csv, " + stem + ".json";
  std::string scenes;
  for (const std::string& s : r.scenes) scenes += (scenes.empty() ? "" : ", ") + s;
  write_pareto_svg(dir + "/tune.svg", tune_plot_points(r, c),
                   "tune: " + scenes + ", objective " + c.objective + " (red squares: best for a budget)",
                   c.objective);
  return "tune.csv, tune.json, tune.svg";
}

}  // namespace shadowlab
