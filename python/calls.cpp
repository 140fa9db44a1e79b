#include "python/calls.h"

#include <algorithm>

#include "core/error.h"
#include "core/parallel.h"
#include "core/spec.h"
#include "core/timer.h"
#include "lab/cli.h"
#include "lab/memory_check.h"
#include "lab/nsm_data_command.h"
#include "lab/output_files.h"
#include "lab/output_folder.h"
#include "lab/provenance.h"
#include "lab/sweep_command.h"
#include "lab/tune_command.h"
#include "lab/tune_report.h"
#include "lab/view_check.h"
#include "raster/gbuffer_pass.h"
#include "raytrace/reference_cache.h"
#include "scenes/scene_registry.h"
#include "techniques/nsm/nsm_technique.h"
#include "techniques/shading/scene_shading.h"

namespace shadowlab::python {

namespace {

Field number(const std::string& name, double v) {
  Field f;
  f.kind = Field::Kind::number;
  f.name = name;
  f.number = v;
  return f;
}
Field integer(const std::string& name, int64_t v) {
  Field f;
  f.kind = Field::Kind::integer;
  f.name = name;
  f.integer = v;
  return f;
}
Field text(const std::string& name, const std::string& v) {
  Field f;
  f.kind = Field::Kind::text;
  f.name = name;
  f.text = v;
  return f;
}
Field none(const std::string& name) {
  Field f;
  f.name = name;
  return f;
}

// Parses `flags` as `program`'s command line declared by `declare` (argv[0] is the program).
template <class Declare>
void parse_flags(const std::string& program, const std::vector<std::string>& flags,
                 Declare declare) {
  CommandLine cl = make_command_line(program, "");
  declare(cl);
  std::vector<std::string> args{program};
  args.insert(args.end(), flags.begin(), flags.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  if (!parse_command_line(cl, int(argv.size()), argv.data()))
    throw InputError(program, "--help is not a call of the module: see help(shadowlab)");
}

bool has_flag(const std::vector<std::string>& flags, const std::string& flag) {
  return std::any_of(flags.begin(), flags.end(), [&](const std::string& f) {
    return f == flag || f.rfind(flag + "=", 0) == 0;
  });
}

// Records the equivalent program's command line as the provenance of the files a call writes,
// so that the command recorded there reproduces the run.
void record_command(const std::string& program, const std::vector<std::string>& flags) {
  std::vector<std::string> args{program};
  args.insert(args.end(), flags.begin(), flags.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  set_run_command(int(argv.size()), argv.data());
}

void add_metric_fields(Fields& out, const MetricReport& m, bool all) {
  for (auto [k, v] : {std::pair{"c10", m.c10}, {"c50", m.c50}, {"c90", m.c90}, {"dark", m.dark},
                      {"lit", m.lit}, {"acne", m.acne}, {"noise", m.noise}, {"detail", m.detail}})
    out.push_back(number(k, v));
  if (!all) return;
  if (m.has_performance) out.push_back(number("performance", m.performance));
  for (auto [k, v] : {std::pair{"fidelity", m.fidelity}, {"aesthetics", m.aesthetics},
                      {"total", m.total}, {"ssim", m.ssim}, {"rmse", m.rmse}, {"psnr", m.psnr},
                      {"flip_mean", m.flip_mean}})
    out.push_back(number(k, v));
}

// One row of sweep.csv as fields, in its columns (write_sweep_csv): empty cells are None.
Fields sweep_row_fields(const std::string& scene, const SweepRow& row) {
  const MetricReport& m = row.report;
  const ShadowResult& r = row.result;
  Fields f{text("scene", scene), text("label", row.label), text("spec", row.spec),
           integer("res", row.res)};
  add_metric_fields(f, m, false);
  f.push_back(number("ssim", m.ssim));
  f.push_back(number("rmse", m.rmse));
  f.push_back(number("psnr", m.psnr));
  const bool timed = !r.from_cache;
  f.push_back(timed ? number("shadow_ms", r.shadow_ms()) : none("shadow_ms"));
  f.push_back(timed ? number("map_ms", r.map_ms) : none("map_ms"));
  f.push_back(timed ? number("lookup_ms", r.lookup_ms) : none("lookup_ms"));
  f.push_back(m.has_performance ? number("performance", m.performance) : none("performance"));
  f.push_back(number("total", m.total));
  f.push_back(number("flip_mean", m.flip_mean));
  f.push_back(number("flip_shaded", row.flip_shaded));
  f.push_back(integer("faces_rendered", r.faces_rendered));
  f.push_back(timed ? number("faces_ms", r.faces_ms) : none("faces_ms"));
  f.push_back(timed ? number("render_ms", r.render_ms) : none("render_ms"));
  f.push_back(timed ? number("filter_ms", r.filter_ms) : none("filter_ms"));
  const WorkCounts w = timed ? r.work : WorkCounts{};
  for (auto [k, v] : {std::pair{"triangles_submitted", w.triangles_submitted},
                      {"triangles_binned", w.triangles_binned},
                      {"texels_rendered", w.texels_rendered},
                      {"texels_filtered", w.texels_filtered},
                      {"pixels_looked_up", w.pixels_looked_up}})
    f.push_back(integer(k, int64_t(v)));
  f.push_back(number("taps_per_pixel", w.taps_per_pixel()));
  f.push_back(integer("bytes_written", int64_t(w.bytes_written)));
  f.push_back(integer("bytes_read", int64_t(w.bytes_read)));
  return f;
}

// One evaluation of tune.csv as fields, in its columns (write_tune_csv).
Fields tune_eval_fields(const TuneEval& e) {
  Fields f{integer("index", int64_t(e.index)), integer("rung", e.rung),
           integer("point", int64_t(e.point)), text("scene", e.scene),
           text("technique", e.technique), text("spec", e.spec), integer("width", e.width),
           integer("height", e.height), integer("spp", e.spp), number("objective", e.objective)};
  for (const auto& [k, m] : tune_report_fields()) f.push_back(number(k, e.report.*m));
  for (auto [k, v] : {std::pair{"faces_ms", e.faces_ms}, {"render_ms", e.render_ms},
                      {"filter_ms", e.filter_ms}, {"map_ms", e.map_ms},
                      {"lookup_ms", e.lookup_ms}, {"shadow_ms", e.shadow_ms()}})
    f.push_back(number(k, v));
  for (const auto& [k, m] : tune_work_fields()) f.push_back(integer(k, int64_t(e.work.*m)));
  return f;
}

}  // namespace

PyScene make_scene(const std::vector<std::string>& flags) {
  CommonOptions o;
  parse_flags("render", flags, [&](CommandLine& cl) { add_common_options(cl, o); });
  if (has_flag(flags, "--out")) throw InputError("--out", "a scene writes no files");
  return PyScene{scene_from_options(o), flags};
}

PyGBuffer make_gbuffer(const PyScene& s, int repeats) {
  if (repeats < 1 || repeats > 100000)
    throw InputError("--repeats", "must lie in [1, 100000], got " + std::to_string(repeats));
  PyGBuffer g;
  g.camera_ms = median_ms(repeats, [&] { render_gbuffer(s.scene, g.g); });
  require_covered_view(s.scene, g.g);
  return g;
}

PyResult render(const PyScene& s, const std::string& spec_text, const PyGBuffer& g, int repeats,
                bool cache, bool texels) {
  if (repeats < 1 || repeats > 100000)
    throw InputError("--repeats", "must lie in [1, 100000], got " + std::to_string(repeats));
  if (g.g.width != s.scene.camera.width || g.g.height != s.scene.camera.height)
    throw InputError("gbuffer", "was made for another image size than the scene's");
  const TechniqueSpec spec = parse_technique_spec(spec_text, "--technique");
  validate_technique(spec, "--technique");
  validate_technique_for_scene(spec, s.scene, "--technique");
  check_run_memory(s.scene, {spec}, 0);
  RunOptions opt;
  opt.repeats = repeats;
  opt.want_texels = texels;
  opt.cache_dir = cache ? default_cache_dir() : "";
  PyResult r;
  r.r = run_technique(spec, s.scene, g.g, opt);
  r.spec = spec.text;
  r.camera_ms = g.camera_ms;
  return r;
}

ImageF shaded_image(const PyResult& r, const PyScene& s, const PyGBuffer& g, double ambient) {
  if (!(ambient >= 0.0 && ambient <= 1.0))
    throw InputError("--ambient", "must lie in [0, 1], got " + std::to_string(ambient));
  if (r.r.mask.width != g.g.width || r.r.mask.height != g.g.height)
    throw InputError("gbuffer", "is not the GBuffer of this result");
  return shade_scene(s.scene, g.g, r.r.mask, float(ambient));
}

Fields result_times(const PyResult& r) {
  const ShadowResult& x = r.r;
  Fields f;
  for (auto [k, v] : {std::pair{"faces_ms", x.faces_ms}, {"render_ms", x.render_ms},
                      {"filter_ms", x.filter_ms}, {"map_ms", x.map_ms},
                      {"lookup_ms", x.lookup_ms}, {"shadow_ms", x.shadow_ms()},
                      {"features_ms", x.features_ms}, {"network_ms", x.network_ms},
                      {"rays_ms", x.rays_ms}, {"denoise_ms", x.denoise_ms},
                      {"camera_ms", r.camera_ms}})
    f.push_back(number(k, v));
  return f;
}

Fields result_work(const PyResult& r) {
  const WorkCounts& w = r.r.work;
  Fields f;
  for (auto [k, v] : {std::pair{"triangles_submitted", w.triangles_submitted},
                      {"triangles_binned", w.triangles_binned},
                      {"texels_rendered", w.texels_rendered},
                      {"texels_filtered", w.texels_filtered},
                      {"pixels_looked_up", w.pixels_looked_up}, {"taps", w.taps},
                      {"bytes_written", w.bytes_written}, {"bytes_read", w.bytes_read},
                      {"multiply_adds", w.multiply_adds},
                      {"activation_bytes", w.activation_bytes}, {"rays", w.rays},
                      {"filter_taps", w.filter_taps}})
    f.push_back(integer(k, int64_t(v)));
  f.push_back(number("taps_per_pixel", w.taps_per_pixel()));
  return f;
}

Fields result_faces(const PyResult& r) {
  const ShadowResult& x = r.r;
  return {integer("total", x.faces_total), integer("needed", x.faces_needed),
          integer("rendered", x.faces_rendered),
          integer("triangles_culled", int64_t(x.triangles_culled))};
}

Fields metric_fields(const ImageF& test, const ImageF& ref, const ImageU32* texels,
                     const double* shadow_ms, double fps) {
  MetricWeights w;
  if (!(fps >= 1e-3 && fps <= 1e6))
    throw InputError("--fps", "must lie in [0.001, 1000000], got " + std::to_string(fps));
  w.target_fps = fps;
  Timings t;
  if (shadow_ms) {
    if (!(*shadow_ms >= 0.0 && *shadow_ms <= 1e9))
      throw InputError("--shadow-ms", "must lie in [0, 1e9], got " + std::to_string(*shadow_ms));
    t.shadowed_ms = *shadow_ms;
  }
  const MetricReport m = compute_metric(test, ref, texels, shadow_ms ? &t : nullptr, w);
  Fields f;
  add_metric_fields(f, m, true);
  return f;
}

std::vector<Fields> resolution_sweep(const std::vector<std::string>& flags) {
  SweepCommand cmd;
  parse_flags("resolution_sweep", flags, [&](CommandLine& cl) { add_sweep_flags(cl, cmd); });
  finish_sweep_command(cmd);
  const bool out_given = has_flag(flags, "--out");
  SweepConfig& c = cmd.config;
  c.progress = false;
  if (c.shards > 1)
    throw InputError("--shard", "the module runs whole sweeps (shard with the program, then merge)");
  if (out_given && !cmd.suite.empty())
    throw InputError("--out", "not with --suite in the module (the program writes a suite's folders)");
  if (cmd.plot_given && !out_given) throw InputError("--plot", "needs --out in the module");
  const std::vector<Scene> scenes = sweep_scenes(cmd);
  std::vector<Fields> rows;
  if (!out_given) {
    c.out_dir.clear();
    for (const Scene& scene : scenes) {
      const SweepResult r = run_resolution_sweep(scene, c);
      rows.push_back(sweep_row_fields(r.scene, r.reference));
      for (const SweepRow& row : r.rows) rows.push_back(sweep_row_fields(r.scene, row));
    }
    return rows;
  }
  record_command("resolution_sweep", flags);
  RunOutputs outputs(cmd.common.out, "--out");
  outputs.check_names({"sweep.csv", "sweep.json", "contact_sheet.png"});
  const std::string plot_file =
      cmd.plot_given ? outputs.file("--plot", cmd.plot, ".svg") : std::string();
  c.out_dir = outputs.dir();
  const SweepResult r = run_resolution_sweep(scenes[0], c);
  write_sweep_files(c.out_dir, r, c, plot_file);
  outputs.commit();
  rows.push_back(sweep_row_fields(r.scene, r.reference));
  for (const SweepRow& row : r.rows) rows.push_back(sweep_row_fields(r.scene, row));
  return rows;
}

std::vector<Fields> tune(const std::vector<std::string>& flags) {
  TuneCommand cmd;
  parse_flags("tune", flags, [&](CommandLine& cl) { add_tune_flags(cl, cmd); });
  finish_tune_command(cmd);
  TuneConfig& c = cmd.config;
  c.progress = false;
  if (c.shards > 1)
    throw InputError("--shard", "the module runs whole searches (shard with the program, then merge)");
  const std::vector<Scene> scenes = tune_scenes(cmd);
  check_tune(scenes, c);
  std::vector<Fields> rows;
  if (cmd.references_only) {
    if (c.cache_dir.empty())
      throw InputError("--references-only", "needs the reference cache (not with --no-cache)");
    tune_references(scenes, c);
    return rows;
  }
  const bool out_given = has_flag(flags, "--out");
  std::unique_ptr<RunOutputs> outputs;
  if (out_given) {
    record_command("tune", flags);
    outputs = std::make_unique<RunOutputs>(cmd.common.out, "--out");
    outputs->check_names({"tune.csv", "tune.json", "tune.svg"});
  }
  const TuneResult r = run_tune(scenes, c);
  if (outputs) {
    std::vector<const Scene*> sp;
    for (const Scene& s : scenes) sp.push_back(&s);
    write_tune_outputs(outputs->dir(), r, c, provenance_json(sp, c.spp, c.repeats));
    outputs->commit();
  }
  for (const TuneEval& e : r.evals)
    if (e.rung == 1) rows.push_back(tune_eval_fields(e));
  return rows;
}

NsmFeatures nsm_features(const PyScene& s, const PyGBuffer& g, const std::string& spec_text,
                         bool every_candidate) {
  const TechniqueSpec spec = parse_technique_spec(spec_text, "--technique");
  if (spec.name != "nsm") throw InputError("--technique", "features are the nsm technique's: got '" + spec.name + "'");
  validate_technique(spec, "--technique");
  validate_technique_for_scene(spec, s.scene, "--technique");
  if (g.g.width != s.scene.camera.width || g.g.height != s.scene.camera.height)
    throw InputError("gbuffer", "was made for another image size than the scene's");
  return nsm_spec_features(spec, s.scene, g.g, every_candidate, "--technique");
}

namespace {

NsmDatasetParams nsm_params(const std::vector<std::string>& flags) {
  NsmDataCommand cmd;
  parse_flags("nsm_data", flags, [&](CommandLine& cl) { add_nsm_data_flags(cl, cmd); });
  finish_nsm_data_command(cmd);
  if (has_flag(flags, "--out")) throw InputError("--out", "a frame is returned, not written");
  return cmd.params;
}

}  // namespace

std::vector<std::string> nsm_frame_splits(const std::vector<std::string>& flags) {
  const NsmDatasetParams p = nsm_params(flags);
  std::vector<std::string> splits;
  for (int i = 0; i < p.frames; ++i) splits.push_back(nsm_frame_split(p, i));
  return splits;
}

std::string nsm_frame(const std::vector<std::string>& flags, int frame) {
  const NsmDatasetParams p = nsm_params(flags);
  if (frame < 0 || frame >= p.frames)
    throw InputError("frame", "must lie in [0, " + std::to_string(p.frames - 1) + "] (--frames " +
                                  std::to_string(p.frames) + "), got " + std::to_string(frame));
  return nsm_frame_file(p, make_builtin_scene(p.scenes[size_t(frame) % p.scenes.size()]), frame);
}

}  // namespace shadowlab::python
