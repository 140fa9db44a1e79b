#include "lab/sweep.h"

#include <algorithm>
#include <set>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/gbuffer_shading.h"
#include "core/output_file.h"
#include "core/repeats.h"
#include "core/timer.h"
#include "lab/view_check.h"
#include "lab/step_progress.h"
#include "lab/contact_sheet.h"
#include "lab/memory_check.h"
#include "util/json_read.h"
#include "lab/output_files.h"
#include "lab/provenance.h"
#include "metric/flip.h"
#include "techniques/shading/scene_shading.h"
#include "raster/gbuffer_pass.h"

namespace shadowlab {
namespace {

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}


}  // namespace

SweepResult run_resolution_sweep(const Scene& scene, const SweepConfig& config) {
  SweepResult out;
  out.scene = scene.name;
  out.width = scene.camera.width;
  out.height = scene.camera.height;
  // Every input is checked before the first expensive step (the camera pass and reference).
  if (config.techniques.empty()) throw InputError("--techniques", "is empty");
  if (config.resolutions.empty()) throw InputError("--resolutions", "is empty");
  reject_repeats("--resolutions", config.resolutions);
  std::vector<TechniqueSpec> specs;
  for (const std::string& t : config.techniques) {
    TechniqueSpec s = parse_technique_spec(t, "--techniques");
    // The sweep's rows are light maps at each resolution; the ray tracer is its reference.
    if (s.name == "rt" || s.name == "rts")
      throw InputError("--techniques", s.name + " has no map resolution: the sweep runs light-map techniques at each of "
                                       "--resolutions against its ray-traced reference (--spp); tune searches rts");
    if (s.params.count("res")) throw InputError("--techniques", "'" + t + "': res is swept by --resolutions");
    specs.push_back(s);
    reject_repeated_specs("--techniques", specs, config.techniques);
    for (int r : config.resolutions) {
      TechniqueSpec probe = s;
      probe.params["res"] = std::to_string(r);
      validate_technique_for_scene(probe, scene, "--techniques");
    }
  }
  // The memory the run needs, checked once the specs are known to be valid: each technique at
  // the largest resolution bounds it.
  {
    std::vector<TechniqueSpec> largest = specs;
    const int res = *std::max_element(config.resolutions.begin(), config.resolutions.end());
    for (TechniqueSpec& s : largest) s.params["res"] = std::to_string(res);
    check_run_memory(scene, largest, config.max_memory);
  }
  const auto start = std::chrono::steady_clock::now();
  const size_t total = 1 + specs.size() * config.resolutions.size();
  size_t done = 0;

  out.provenance = provenance_json({&scene}, config.spp, config.repeats);
  GBuffer g;
  out.camera_ms = median_ms(config.repeats, [&] { render_gbuffer(scene, g); });
  require_covered_view(scene, g);  // before the reference: an empty view scores nothing
  // The shaded images' normals and uvs, once for every row (untimed: only the pictures need
  // them, core/gbuffer_shading.h).
  fill_shading_attributes(scene, g);
  MetricWeights weights;
  weights.target_fps = config.target_fps;
  MetricScratch scratch;  // one set of metric buffers for every row

  // Reference first: the mask every row is compared with.
  step_progress_line(config.progress, done, total, "reference", start);
  const TechniqueSpec ref_spec =
      parse_technique_spec("rt:spp=" + std::to_string(config.spp), "--spp");
  RunOptions ref_opt;
  ref_opt.repeats = 1;  // the reference is not what is being timed; run it once
  ref_opt.cache_dir = config.cache_dir;
  ref_opt.flag = "--spp";
  ref_opt.progress = config.progress;
  out.reference.spec = ref_spec.text;
  out.reference.label = "RT " + std::to_string(config.spp) + "spp";
  out.reference.technique = ref_spec.name;
  out.reference.result = run_technique(ref_spec, scene, g, ref_opt);
  out.reference.report = compute_metric(out.reference.result.mask, out.reference.result.mask,
                                         nullptr, nullptr, weights, &scratch);
  // Shaded images: written beside the masks, kept downscaled to the contact sheet's cell, and
  // scored by FLIP against the reference's (metric/flip.h: what a person sees; the reference's
  // half prepared once), with the error map beside them on request (--flip-map).
  const int cell_factor = contact_sheet_layout({}, {}, g.width, g.height, true).factor;
  FlipPrepared ref_shaded;
  auto shade = [&](SweepRow& row, const std::string& prefix, const std::string& spec_text) {
    const ImageF shaded = shade_scene(scene, g, row.result.mask, config.ambient);
    row.shaded_cell = box_downscale(shaded, cell_factor);
    const FlipPrepared prepared = flip_prepare(shaded);
    if (ref_shaded.width == 0) ref_shaded = prepared;  // the reference comes first
    const ImageF flip = flip_error_map(prepared, ref_shaded);
    row.flip_shaded = flip_mean(flip);
    if (!config.out_dir.empty()) {
      write_result_files(config.out_dir, prefix, row.result, spec_text, out.camera_ms, out.provenance,
                         &shaded);
      if (config.flip_map) write_flip_map(config.out_dir + "/" + prefix + "flip", flip, out.provenance);
    }
  };
  shade(out.reference, "reference_", ref_spec.text);
  step_progress_line(config.progress, ++done, total, "reference", start);

  out.rows_total = specs.size() * config.resolutions.size();
  out.shard = config.shard;
  out.shards = config.shards;
  size_t index = 0;
  for (const TechniqueSpec& base : specs)
    for (int res : config.resolutions) {
      const size_t row_index = index++;
      if (row_index % size_t(config.shards) != size_t(config.shard)) continue;
      TechniqueSpec spec = base;
      spec.params["res"] = std::to_string(res);
      spec.text = spec_text(spec);
      SweepRow row;
      row.spec = spec.text;
      row.res = res;
      row.index = row_index;
      row.technique = base.name;
      row.label = upper(base.text) + " " + std::to_string(res);
      step_progress_line(config.progress, done, total, row.label, start);
      RunOptions opt;
      opt.repeats = config.repeats;
      opt.flag = "--techniques";
      row.result = run_technique(spec, scene, g, opt);
      const Timings t{out.camera_ms + row.result.shadow_ms(), out.camera_ms};
      row.report = compute_metric(row.result.mask, out.reference.result.mask,
                                  row.result.texels.empty() ? nullptr : &row.result.texels, &t,
                                  weights, &scratch);
      std::string prefix = base.text + "_" + std::to_string(res) + "_";
      std::replace_if(prefix.begin(), prefix.end(), [](char c) { return c == ':' || c == ',' || c == '='; }, '_');
      shade(row, prefix, spec.text);
      out.rows.push_back(std::move(row));
      step_progress_line(config.progress, ++done, total, out.rows.back().label, start);
    }
  return out;
}

std::string sweep_table(const SweepResult& r) {
  std::string s;
  // The label column fits the longest label (at least 18 wide: "CSM 1024", "RT 1024spp").
  int w = 18;
  for (const SweepRow& row : r.rows) w = std::max(w, int(std::min<size_t>(row.label.size(), 200)));
  s += fmt::format("{:<{}} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>7} {:>10} {:>6} {:>6} {:>6} {:>8} {:>7} {:>7}\n",
                   "method", w, "c10", "c50", "c90", "dark", "lit", "acne", "noise", "detail",
                   "shadow ms", "RP", "total", "FLIP", "Mtexels", "taps/px", "MB");
  auto add = [&](const SweepRow& row, bool is_ref) {
    const MetricReport& m = row.report;
    const std::string time =
        row.result.from_cache ? "cached" : fmt::format("{:.2f}", row.result.shadow_ms());
    const std::string rp = is_ref ? "-" : fmt::format("{:.3f}", m.performance);
    const std::string total = fmt::format("{:.3f}", m.total);
    // Work counts (docs/metric.md): texels rendered, mean taps per looked-up pixel, map
    // bytes touched (written + read), all per repeat; "-" for the ray tracer.
    const WorkCounts& wk = row.result.work;
    std::string tex = "-", taps = "-", mb = "-";
    if (!is_ref) {
      tex = fmt::format("{:.2f}", double(wk.texels_rendered) * 1e-6);
      taps = fmt::format("{:.1f}", wk.taps_per_pixel());
      mb = fmt::format("{:.1f}", double(wk.bytes_touched()) * 1e-6);
    }
    s += fmt::format(
        "{:<{}} {:6.3f} {:6.3f} {:6.3f} {:6.3f} {:6.3f} {:6.3f} {:6.3f} {:7.3f} {:>10} {:>6} {:>6} {:6.4f} {:>8} {:>7} {:>7}\n",
        row.label, w, m.c10, m.c50, m.c90, m.dark, m.lit, m.acne, m.noise, m.detail, time, rp,
        total, m.flip_mean, tex, taps, mb);
  };
  add(r.reference, true);
  for (const SweepRow& row : r.rows) add(row, false);
  return s;
}

namespace {

nlohmann::json row_json(const SweepRow& row) {
  const MetricReport& m = row.report;
  nlohmann::json j;
  j["label"] = row.label;
  j["index"] = row.index;
  j["technique"] = row.technique;
  j["spec"] = row.spec;
  j["res"] = row.res;
  for (const auto& [k, v] : std::initializer_list<std::pair<const char*, double>>{
           {"c10", m.c10}, {"c50", m.c50}, {"c90", m.c90}, {"dark", m.dark}, {"lit", m.lit},
           {"acne", m.acne}, {"noise", m.noise}, {"detail", m.detail},
           {"fidelity", m.fidelity}, {"aesthetics", m.aesthetics}, {"ssim", m.ssim},
           {"rmse", m.rmse}, {"psnr", m.psnr}, {"total", m.total}, {"flip_mean", m.flip_mean},
           {"flip_shaded", row.flip_shaded}})
    j[k] = v;
  if (m.has_performance) j["performance"] = m.performance;
  j.update(timing_json(row.result));
  j["faces_needed"] = row.result.faces_needed;
  j["faces_rendered"] = row.result.faces_rendered;
  j["from_cache"] = row.result.from_cache;
  j["notes"] = row.result.notes;
  return j;
}

}  // namespace

void write_sweep_csv(const std::string& path, const SweepResult& r) {
  write_sweep_csv(path, std::vector<const SweepResult*>{&r});
}

void write_sweep_csv(const std::string& path, const std::vector<const SweepResult*>& results) {
  std::ostringstream f;
  // One "# provenance {...}" line per scene before the header (pandas: comment='#').
  for (const SweepResult* r : results) f << "# provenance " << r->provenance.dump() << "\n";
  f << "scene,label,spec,res,c10,c50,c90,dark,lit,acne,noise,detail,ssim,rmse,psnr,shadow_ms,map_ms,"
       "lookup_ms,performance,total,flip_mean,flip_shaded,faces_rendered," << work_csv_header() << "\n";
  const SweepResult* current = nullptr;
  auto add = [&](const SweepRow& row) {
    const MetricReport& m = row.report;
    f << "\"" << current->scene << "\",";
    // Label and spec are quoted: a spec's keys are comma-separated (neither holds a quote).
    // Empty fields where there is no value: the times of a cached reference, the performance
    // score of a row without timings (the reference).
    std::string shadow, map, lookup, perf;
    if (!row.result.from_cache) {
      shadow = fmt::format("{:.4f}", row.result.shadow_ms());
      map = fmt::format("{:.4f}", row.result.map_ms);
      lookup = fmt::format("{:.4f}", row.result.lookup_ms);
    }
    if (m.has_performance) perf = fmt::format("{:.6f}", m.performance);
    f << fmt::format(
             "\"{}\",\"{}\",{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.4f},"
             "{},{},{},{},{:.6f},{:.6f},{:.6f},{},",
             row.label, row.spec, row.res, m.c10, m.c50, m.c90, m.dark, m.lit, m.acne, m.noise,
             m.detail, m.ssim, m.rmse, m.psnr, shadow, map, lookup, perf, m.total, m.flip_mean,
             row.flip_shaded, row.result.faces_rendered)
      << work_csv_values(row.result) << "\n";
  };
  for (const SweepResult* r : results) {
    current = r;
    add(r->reference);
    for (const SweepRow& row : r->rows) add(row);
  }
  write_text_file(path, f.str());
}

std::string suite_table(const std::vector<SweepResult>& results) {
  SL_CHECK(!results.empty());
  const size_t n = results[0].rows.size();
  for (const SweepResult& r : results) SL_CHECK_EQ(r.rows.size(), n);
  size_t label_w = 18;
  for (const SweepRow& row : results[0].rows) label_w = std::max(label_w, row.label.size() + 2);
  std::string s;
  auto block = [&](const char* title, auto value) {
    s += fmt::format("{:<{}}", title, label_w);
    for (const SweepResult& r : results) s += fmt::format(" {:>11}", r.scene.substr(0, 11));
    s += fmt::format(" {:>8} {:>8}  {}\n", "mean", "worst", "worst on");
    for (size_t i = 0; i < n; ++i) {
      s += fmt::format("{:<{}}", results[0].rows[i].label, label_w);
      double sum = 0.0, worst = 1e300;
      std::string worst_scene;
      for (const SweepResult& r : results) {
        const double v = value(r.rows[i].report);
        s += fmt::format(" {:>11.3f}", v);
        sum += v;
        if (v < worst) worst = v, worst_scene = r.scene;
      }
      s += fmt::format(" {:>8.3f} {:>8.3f}  {}\n", sum / double(results.size()), worst, worst_scene);
    }
  };
  block("fidelity", [](const MetricReport& m) { return m.fidelity; });
  block("total", [](const MetricReport& m) { return m.total; });
  return s;
}

void write_sweep_json(const std::string& path, const SweepResult& r) {
  write_text_file(path, sweep_json(r).dump(2) + "\n");
}

nlohmann::json sweep_json(const SweepResult& r) {
  nlohmann::json j;
  j["kind"] = "sweep";
  j["provenance"] = r.provenance;
  j["rows_total"] = r.rows_total;
  j["shard"] = r.shard;
  j["shards"] = r.shards;
  j["scene"] = r.scene;
  j["width"] = r.width;
  j["height"] = r.height;
  j["camera_ms"] = r.camera_ms;
  j["reference"] = row_json(r.reference);
  j["rows"] = nlohmann::json::array();
  for (const SweepRow& row : r.rows) j["rows"].push_back(row_json(row));
  return j;
}

std::vector<PlotPoint> sweep_plot_points(const SweepResult& r) {
  std::vector<PlotPoint> points;
  for (const SweepRow& row : r.rows)
    points.push_back({row.label, row.technique, row.result.shadow_ms(), row.report.total,
                      row.report.fidelity, double(row.result.work.bytes_touched())});
  return points;
}

std::string sweep_caption(const SweepRow& row) { return fmt::format("total {:.3f}", row.report.total); }

ImageF sweep_contact_sheet(const SweepResult& r, const SweepConfig& config) {
  const size_t n_res = config.resolutions.size();
  // run_resolution_sweep appends rows technique-major, resolution-minor.
  SL_CHECK_EQ(r.rows.size(), config.techniques.size() * n_res);
  std::vector<std::string> row_labels, col_labels;
  std::vector<std::vector<const ImageF*>> cells;
  std::vector<std::vector<std::string>> captions;
  auto cell = [&](const SweepRow& row) {
    return config.shaded_sheet ? &row.shaded_cell : &row.result.mask;
  };
  for (size_t t = 0; t < config.techniques.size(); ++t) {
    // The same text as the rows' labels: the canonical spec, upper case.
    row_labels.push_back(upper(parse_technique_spec(config.techniques[t], "--techniques").text));
    cells.emplace_back();
    captions.emplace_back();
    for (size_t j = 0; j < n_res; ++j) {
      const SweepRow& row = r.rows[t * n_res + j];
      cells.back().push_back(cell(row));
      captions.back().push_back(sweep_caption(row));
    }
  }
  for (int res : config.resolutions) col_labels.push_back(std::to_string(res));
  return contact_sheet(row_labels, col_labels, cells, cell(r.reference), {}, &captions);
}

namespace {

SweepRow row_from_json(const nlohmann::json& j, const std::string& where) {
  SweepRow row;
  row.label = json_string(j, "label", where);
  row.index = json_uint(j, "index", uint64_t(1) << 40, where);
  row.technique = json_string(j, "technique", where);
  row.spec = json_string(j, "spec", where);
  row.res = int(json_uint(j, "res", 1 << 20, where));
  MetricReport& m = row.report;
  for (const auto& [k, v] : std::initializer_list<std::pair<const char*, double MetricReport::*>>{
           {"c10", &MetricReport::c10}, {"c50", &MetricReport::c50}, {"c90", &MetricReport::c90},
           {"dark", &MetricReport::dark}, {"lit", &MetricReport::lit}, {"acne", &MetricReport::acne},
           {"noise", &MetricReport::noise}, {"detail", &MetricReport::detail},
           {"fidelity", &MetricReport::fidelity}, {"aesthetics", &MetricReport::aesthetics},
           {"ssim", &MetricReport::ssim}, {"rmse", &MetricReport::rmse}, {"psnr", &MetricReport::psnr},
           {"total", &MetricReport::total}})
    m.*v = json_number(j, k, where);
  // Files written before FLIP joined the metric have neither key (NaN then: "not measured").
  m.flip_mean = j.contains("flip_mean") ? json_number(j, "flip_mean", where) : std::nan("");
  row.flip_shaded = j.contains("flip_shaded") ? json_number(j, "flip_shaded", where) : std::nan("");
  m.has_performance = j.contains("performance");
  if (m.has_performance) m.performance = json_number(j, "performance", where);
  ShadowResult& r = row.result;
  r.from_cache = json_bool(j, "from_cache", where);
  auto ms = [&](const char* k) { return json_at(j, k, where).is_null() ? 0.0 : json_number(j, k, where); };
  r.faces_ms = ms("faces_ms");
  r.render_ms = ms("render_ms");
  r.filter_ms = ms("filter_ms");
  r.map_ms = ms("map_ms");
  r.lookup_ms = ms("lookup_ms");
  const nlohmann::json& w = json_at(j, "work", where);
  r.work.triangles_submitted = json_uint(w, "triangles_submitted", UINT64_MAX, where);
  r.work.triangles_binned = json_uint(w, "triangles_binned", UINT64_MAX, where);
  r.work.texels_rendered = json_uint(w, "texels_rendered", UINT64_MAX, where);
  r.work.texels_filtered = json_uint(w, "texels_filtered", UINT64_MAX, where);
  r.work.pixels_looked_up = json_uint(w, "pixels_looked_up", UINT64_MAX, where);
  r.work.taps = json_uint(w, "taps", UINT64_MAX, where);
  r.work.bytes_written = json_uint(w, "bytes_written", UINT64_MAX, where);
  r.work.bytes_read = json_uint(w, "bytes_read", UINT64_MAX, where);
  r.faces_needed = int(json_uint(j, "faces_needed", 64, where));
  r.faces_rendered = int(json_uint(j, "faces_rendered", 64, where));
  r.notes = json_string(j, "notes", where);
  return row;
}

}  // namespace

SweepResult sweep_from_json(const nlohmann::json& j, const std::string& where) {
  try {
    if (!j.contains("kind") || j.at("kind") != "sweep") throw InputError(where, "not a resolution_sweep result");
    SweepResult r;
    r.scene = json_string(j, "scene", where);
    r.width = int(json_uint(j, "width", 1 << 20, where));
    r.height = int(json_uint(j, "height", 1 << 20, where));
    r.camera_ms = json_number(j, "camera_ms", where);
    r.provenance = json_at(j, "provenance", where);
    r.rows_total = json_uint(j, "rows_total", uint64_t(1) << 40, where);
    r.shards = int(std::max<uint64_t>(1, json_uint(j, "shards", 100000, where)));
    r.shard = int(json_uint(j, "shard", uint64_t(r.shards - 1), where));
    if (!r.provenance.is_object() || !r.provenance.contains("command") || !r.provenance["command"].is_array())
      throw InputError(where, "its provenance has no command");
    r.reference = row_from_json(json_at(j, "reference", where), where);
    for (const nlohmann::json& row : json_array(j, "rows", where)) r.rows.push_back(row_from_json(row, where));
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(where, "malformed resolution_sweep result: " + json_error_text(e));
  }
}

SweepResult merge_sweep_shards(const std::vector<nlohmann::json>& shards,
                               const std::vector<std::string>& paths) {
  SweepResult merged = sweep_from_json(shards.at(0), paths.at(0));
  merged.rows.clear();
  if (int(shards.size()) != merged.shards)
    throw InputError(paths[0], fmt::format("is one of {} shards, {} files given", merged.shards, shards.size()));
  // What determines the scores must agree: the run's command but --shard and --out, the build,
  // the scenes. Machine, date and threads may differ.
  auto key = [](const nlohmann::json& p, const std::string& where) {
    nlohmann::json k = p;
    for (const char* f : {"date", "cpu", "threads"}) k.erase(f);
    const std::vector<std::string> cmd =
        command_without(json_strings(p, "command", where), {"--shard", "--out", "--threads"});
    k["command"] = cmd;
    return k;
  };
  const nlohmann::json key0 = key(merged.provenance, paths[0]);
  std::set<int> seen;
  for (size_t i = 0; i < shards.size(); ++i) {
    SweepResult r = sweep_from_json(shards[i], paths[i]);
    const nlohmann::json k = key(r.provenance, paths[i]);
    if (k != key0) throw InputError(paths[i], provenance_difference(k, key0, paths[0]));
    if (r.shards != merged.shards || r.rows_total != merged.rows_total || r.scene != merged.scene)
      throw InputError(paths[i], "is a shard of another sweep than " + paths[0]);
    if (!seen.insert(r.shard).second) throw InputError(paths[i], fmt::format("shard {} given twice", r.shard));
    for (SweepRow& row : r.rows) {
      if (row.index >= merged.rows_total || int(row.index % size_t(merged.shards)) != r.shard)
        throw InputError(paths[i], fmt::format("row {} does not belong to shard {}/{}", row.index, r.shard, merged.shards));
      merged.rows.push_back(std::move(row));
    }
  }
  std::sort(merged.rows.begin(), merged.rows.end(), [](const SweepRow& a, const SweepRow& b) { return a.index < b.index; });
  for (size_t k = 0; k < merged.rows.size(); ++k)
    if (merged.rows[k].index != k)
      throw InputError("merge", fmt::format("row {} is {}", k, merged.rows[k].index < k ? "present twice" : "missing"));
  if (merged.rows.size() != merged.rows_total)
    throw InputError("merge", fmt::format("{} of {} rows present", merged.rows.size(), merged.rows_total));
  merged.shard = 0;
  merged.shards = 1;
  return merged;
}

}  // namespace shadowlab
