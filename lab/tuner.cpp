#include "lab/tuner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "core/repeats.h"
#include "core/timer.h"
#include "lab/view_check.h"
#include "lab/step_progress.h"
#include "lab/memory_check.h"
#include "util/pareto_plot.h"
#include "raster/gbuffer_pass.h"
#include "techniques/registry/technique_spec.h"

namespace shadowlab {
namespace {

struct Point {
  TechniqueSpec spec;
  size_t space = 0;
};

// One scene at one rung's size: its GBuffer, reference mask and (with a performance weight)
// unshadowed camera time.
struct SceneRung {
  Scene scene;
  GBuffer g;
  ImageF reference;
  double camera_ms = 0.0;
};

size_t total_points(const TuneConfig& c) {
  size_t n = 0;
  for (const ParamSpace& s : c.spaces) {
    const size_t k = s.size();
    if (k > std::numeric_limits<size_t>::max() - n) return std::numeric_limits<size_t>::max();
    n += k;
  }
  return n;
}

std::string resolved_strategy(const TuneConfig& c, size_t evaluations) {
  if (c.strategy != "auto") return c.strategy;
  return evaluations <= kAutoGridPoints ? "grid" : "halving";
}

// Rung 0's image: 1/small_divisor per axis, at least 16 pixels.
Scene rung_scene(const Scene& s, int rung, const TuneConfig& c) {
  Scene out = s;
  if (rung == 0) {
    out.camera.width = std::max(16, s.camera.width / c.small_divisor);
    out.camera.height = std::max(16, s.camera.height / c.small_divisor);
  }
  return out;
}

std::vector<Point> expand_points(const TuneConfig& c) {
  std::vector<Point> points;
  for (size_t s = 0; s < c.spaces.size(); ++s)
    for (size_t i = 0; i < c.spaces[s].size(); ++i)
      points.push_back({parse_technique_spec(space_point(c.spaces[s], i), "--space"), s});
  return points;
}

SceneRung prepare(const Scene& scene, int rung, const TuneConfig& c) {
  SceneRung r;
  r.scene = rung_scene(scene, rung, c);
  render_gbuffer(r.scene, r.g);
  require_covered_view(r.scene, r.g);  // before the reference: an empty view scores nothing
  if (c.weights.performance > 0.0)
    r.camera_ms = median_ms(c.repeats, [&] { render_gbuffer(r.scene, r.g); });
  const int spp = rung == 0 ? c.small_spp : c.spp;
  RunOptions opt;
  opt.repeats = 1;
  opt.cache_dir = c.cache_dir;
  opt.flag = "--spp";
  opt.progress = c.progress;
  r.reference = run_technique(parse_technique_spec("rt:spp=" + std::to_string(spp), "--spp"),
                              r.scene, r.g, opt)
                    .mask;
  return r;
}

TuneEval evaluate(const Point& p, const SceneRung& sr, int rung, const TuneConfig& c,
                  MetricScratch& scratch) {
  RunOptions opt;
  opt.repeats = c.repeats;
  opt.flag = "--space";
  const ShadowResult res = run_technique(p.spec, sr.scene, sr.g, opt);
  TuneEval e;
  e.rung = rung;
  e.scene = sr.scene.name;
  e.technique = p.spec.name;
  e.spec = p.spec.text;
  e.width = sr.scene.camera.width;
  e.height = sr.scene.camera.height;
  e.spp = rung == 0 ? c.small_spp : c.spp;
  const Timings t{sr.camera_ms + res.shadow_ms(), sr.camera_ms};
  e.report = compute_metric(res.mask, sr.reference, res.texels.empty() ? nullptr : &res.texels,
                            c.weights.performance > 0.0 ? &t : nullptr, c.weights, &scratch);
  e.objective = objective_value(e.report, c.objective);
  e.faces_ms = res.faces_ms;
  e.render_ms = res.render_ms;
  e.filter_ms = res.filter_ms;
  e.map_ms = res.map_ms;
  e.lookup_ms = res.lookup_ms;
  e.work = res.work;
  return e;
}


}  // namespace

const std::vector<std::string>& tune_objectives() {
  static const std::vector<std::string> names = {
      "total", "fidelity", "aesthetics", "detail", "ssim", "psnr", "c10", "c50", "c90",
      "dark",  "lit",      "acne",       "noise", "flip"};
  return names;
}

double objective_value(const MetricReport& m, const std::string& o) {
  if (o == "total") return m.total;
  if (o == "fidelity") return m.fidelity;
  if (o == "aesthetics") return m.aesthetics;
  if (o == "detail") return m.detail;
  if (o == "ssim") return m.ssim;
  if (o == "psnr") return m.psnr;
  if (o == "c10") return m.c10;
  if (o == "c50") return m.c50;
  if (o == "c90") return m.c90;
  if (o == "dark") return m.dark;
  if (o == "lit") return m.lit;
  if (o == "acne") return m.acne;
  if (o == "noise") return m.noise;
  if (o == "flip") return 1.0 - m.flip_mean;  // maximized: 1 − mean FLIP of the masks
  std::string list;
  for (const std::string& n : tune_objectives()) list += (list.empty() ? "" : ", ") + n;
  throw InputError("--objective", "unknown objective '" + o + "' (one of: " + list + ")");
}

std::vector<size_t> halving_survivors(const std::vector<double>& objective,
                                      const std::vector<double>& bytes, int eta) {
  const size_t n = objective.size();
  const size_t want = (n + size_t(eta) - 1) / size_t(eta);
  std::vector<bool> kept(n, false);
  size_t count = 0;
  while (count < want) {
    std::vector<size_t> rest;
    std::vector<double> cost, score;
    for (size_t i = 0; i < n; ++i)
      if (!kept[i]) {
        rest.push_back(i);
        cost.push_back(bytes[i]);
        score.push_back(objective[i]);
      }
    if (rest.empty()) break;
    const std::vector<bool> front = pareto_front(cost, score);
    bool any = false;
    for (size_t k = 0; k < rest.size(); ++k)
      if (front[k]) {
        kept[rest[k]] = true;
        ++count;
        any = true;
      }
    if (!any) {  // only NaN scores left: keep them all rather than loop
      for (size_t i : rest) kept[i] = true;
      break;
    }
  }
  std::vector<size_t> out;
  for (size_t i = 0; i < n; ++i)
    if (kept[i]) out.push_back(i);
  return out;
}

void check_tune(const std::vector<Scene>& scenes, const TuneConfig& c) {
  if (c.spaces.empty()) throw InputError("--space", "no space given");
  objective_value(MetricReport{}, c.objective);
  for (double b : c.budgets_ms)
    if (!(b > 0.0)) throw InputError("--budget-ms", "budgets must be > 0");
  for (double b : c.budgets_bytes)
    if (!(b > 0.0)) throw InputError("--budget-bytes", "budgets must be > 0");
  if (c.budgets_ms.empty() && c.budgets_bytes.empty())
    throw InputError("--budget-ms", "give --budget-ms and/or --budget-bytes");
  if (c.strategy != "auto" && c.strategy != "grid" && c.strategy != "halving")
    throw InputError("--strategy", "expected grid, halving or auto, got '" + c.strategy + "'");
  reject_repeats("--space", c.spaces, same_space,
                 [&](size_t i) { return c.spaces[i].text; });
  // The point count before expanding anything: a space can describe billions of points.
  const size_t points = total_points(c);
  const size_t evals = points > std::numeric_limits<size_t>::max() / std::max<size_t>(1, scenes.size())
                           ? std::numeric_limits<size_t>::max()
                           : points * scenes.size();
  const std::string strategy = resolved_strategy(c, evals);
  if (strategy == "grid" && evals > c.max_evals)
    throw InputError("--space", std::to_string(points) + " points x " + std::to_string(scenes.size()) +
                                    " scene(s) = " + (evals == std::numeric_limits<size_t>::max() ? std::string("too many") : std::to_string(evals)) +
                                    " evaluations, more than --max-evals " + std::to_string(c.max_evals) +
                                    " for --strategy grid (use --strategy halving or a smaller space)");
  if (strategy == "halving") {
    // Cost in full-size evaluations: rung 0 at 1/divisor² of the pixels, plus the survivors.
    const double d2 = double(c.small_divisor) * double(c.small_divisor);
    const double cost = double(evals) / d2 + double(evals) / double(c.eta);
    if (!(cost <= double(c.max_evals)))
      throw InputError("--space", std::to_string(points) + " points: successive halving would cost about " +
                                      std::to_string(size_t(cost)) + " full-size evaluations, more than --max-evals " +
                                      std::to_string(c.max_evals));
    if (c.shards > 1)
      throw InputError("--shard", "needs --strategy grid (successive halving's second rung depends on every shard's first)");
  }
  // One expansion for every check below.
  const std::vector<Point> expanded = expand_points(c);
  std::vector<TechniqueSpec> specs;
  for (const Point& p : expanded) {
    for (const Scene& s : scenes) validate_technique_for_scene(p.spec, s, "--space");
    specs.push_back(p.spec);
  }
  // Two spaces may share a point; its files and rows would be ambiguous.
  std::vector<std::string> sorted;
  for (const Point& p : expanded) sorted.push_back(p.spec.text);
  std::sort(sorted.begin(), sorted.end());
  const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
  if (dup != sorted.end()) throw InputError("--space", "point '" + *dup + "' occurs in two spaces");
  // Memory: the techniques run one at a time; every point bounds it.
  for (const Scene& s : scenes) check_run_memory(s, specs, c.max_memory);
}

void tune_references(const std::vector<Scene>& scenes, const TuneConfig& c) {
  check_tune(scenes, c);
  const size_t evals = total_points(c) * scenes.size();
  const bool halving = resolved_strategy(c, evals) == "halving";
  for (const Scene& s : scenes) {
    if (halving) prepare(s, 0, c);
    prepare(s, 1, c);
  }
}

TuneResult run_tune(const std::vector<Scene>& scenes, const TuneConfig& c) {
  check_tune(scenes, c);
  const std::vector<Point> points = expand_points(c);
  const size_t n_scenes = scenes.size();
  TuneResult out;
  for (const Scene& s : scenes) out.scenes.push_back(s.name);
  for (const Point& p : points) out.points.push_back(p.spec.text);
  out.strategy = resolved_strategy(c, points.size() * n_scenes);
  const auto start = std::chrono::steady_clock::now();
  MetricScratch scratch;

  // The points rung 1 evaluates: all (grid), or halving's survivors of rung 0.
  std::vector<size_t> full;
  if (out.strategy == "grid") {
    for (size_t i = 0; i < points.size(); ++i) full.push_back(i);
  } else {
    out.rung_total[0] = points.size() * n_scenes;
    std::vector<double> obj(points.size(), 0.0), bytes(points.size(), 0.0);
    size_t done0 = 0;
    for (size_t si = 0; si < n_scenes; ++si) {
      const SceneRung sr = prepare(scenes[si], 0, c);
      for (size_t pi = 0; pi < points.size(); ++pi) {
        step_progress_line(c.progress, done0++, out.rung_total[0], "rung 0: " + points[pi].spec.text, start);
        TuneEval e = evaluate(points[pi], sr, 0, c, scratch);
        e.index = pi * n_scenes + si;
        e.point = pi;
        out.evals.push_back(std::move(e));
      }
    }
    step_progress_line(c.progress, out.rung_total[0], out.rung_total[0], "rung 0", start);
    std::sort(out.evals.begin(), out.evals.end(), [](const TuneEval& a, const TuneEval& b) { return a.index < b.index; });
    // Aggregate over scenes in scene order: mean objective, largest bytes.
    for (const TuneEval& e : out.evals) {
      obj[e.point] += e.objective / double(n_scenes);
      bytes[e.point] = std::max(bytes[e.point], double(e.work.bytes_touched()));
    }
    for (size_t s = 0; s < c.spaces.size(); ++s) {
      std::vector<size_t> members;
      std::vector<double> o, b;
      for (size_t i = 0; i < points.size(); ++i)
        if (points[i].space == s) {
          members.push_back(i);
          o.push_back(obj[i]);
          b.push_back(bytes[i]);
        }
      for (size_t k : halving_survivors(o, b, c.eta)) full.push_back(members[k]);
    }
  }
  out.rung_total[1] = full.size() * n_scenes;
  // Rung 1, scene by scene (one GBuffer and reference at a time); the evaluation index is the
  // survivor's position × scenes + scene, and a shard takes index mod shards == shard.
  std::vector<TuneEval> rung1;
  size_t mine = 0, done = 0;
  for (size_t k = 0; k < out.rung_total[1]; ++k) mine += k % size_t(c.shards) == size_t(c.shard);
  for (size_t si = 0; si < n_scenes; ++si) {
    bool any = false;
    for (size_t k = 0; k < full.size(); ++k) any |= (k * n_scenes + si) % size_t(c.shards) == size_t(c.shard);
    if (!any) continue;
    const SceneRung sr = prepare(scenes[si], 1, c);
    for (size_t k = 0; k < full.size(); ++k) {
      const size_t index = k * n_scenes + si;
      if (index % size_t(c.shards) != size_t(c.shard)) continue;
      step_progress_line(c.progress, done, mine, points[full[k]].spec.text, start);
      TuneEval e = evaluate(points[full[k]], sr, 1, c, scratch);
      e.index = index;
      e.point = full[k];
      rung1.push_back(std::move(e));
      ++done;
    }
  }
  step_progress_line(c.progress, mine, mine, "done", start);
  std::sort(rung1.begin(), rung1.end(), [](const TuneEval& a, const TuneEval& b) { return a.index < b.index; });
  for (TuneEval& e : rung1) out.evals.push_back(std::move(e));
  return out;
}

}  // namespace shadowlab
