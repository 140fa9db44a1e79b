#include "lab/sweep_command.h"

#include "core/error.h"
#include "core/image_io.h"
#include "raytrace/reference_cache.h"
#include "scenes/scene_registry.h"
#include "techniques/registry/technique.h"

namespace shadowlab {

void add_sweep_flags(CommandLine& cl, SweepCommand& cmd) {
  add_common_options(cl, cmd.common);
  SweepConfig& c = cmd.config;
  add_text(cl, "--techniques", "LIST", "comma-separated light-map technique specs without res (the ray tracer is the reference: --spp) (default: csm)", cmd.techniques);
  add_int_list(cl, "--resolutions", "LIST", "shadow-map resolutions (default: 128,256,512,1024)", c.resolutions, 1, 8192);
  add_int(cl, "--spp", "N", "reference samples per pixel (default 256; 1024 = the paper)", cmd.spp, 1, 1 << 20);
  add_int(cl, "--repeats", "N", "timed runs, the median reported (default 5; 3 with --quick)", cmd.repeats, 1, 100000);
  add_switch(cl, "--quick", "CI size: 320x240, 64 spp, 3 repeats (explicit flags still win)", cmd.quick);
  add_switch(cl, "--no-cache", "do not read or write the reference cache", cmd.no_cache);
  add_text(cl, "--plot", "FILE.svg", "also write score-vs-time plots with Pareto fronts (default: none)", cmd.plot, &cmd.plot_given);
  add_text(cl, "--sheet", "KIND", "contact sheet of masks or shaded images: mask or shaded (default mask)", cmd.sheet);
  add_double(cl, "--ambient", "A", "ambient level of the shaded images, [0, 1] (default 0.1)", cmd.ambient, 0.0, 1.0);
  add_switch(cl, "--flip-map", "also write each row's LDR-FLIP error map of its shaded image against the reference's (PREFIX_flip.exr, .png)", c.flip_map);
  add_text(cl, "--suite", "NAME", "run every scene of a suite (hard: grazing, contact, depth_range, cluttered; all: those + default, foliage, bunny) instead of --scene: a table per scene in --out/SCENE/, then each setting's fidelity and total per scene with the mean and the worst (default: none)", cmd.suite);
  add_text(cl, "--shard", "i/N", "run only the rows (technique x resolution, in order) with index mod N == i, writing sweep_shardIofN.csv/.json; combine with build/programs/merge (default 0/1)", cmd.shard);
}

void finish_sweep_command(SweepCommand& cmd) {
  SweepConfig& c = cmd.config;
  CommonOptions& common = cmd.common;
  if (!cmd.shard.empty()) parse_shard(cmd.shard, c.shard, c.shards);
  if (!cmd.suite.empty()) {
    cmd.suite_scenes = scene_suite(cmd.suite, "--suite");
    reject_scene_with_suite(common);
    if (!cmd.plot.empty() || cmd.plot_given) throw InputError("--plot", "is per scene; not with --suite");
    if (c.shards > 1) throw InputError("--shard", "not with --suite (shard each scene's sweep instead)");
  }
  if (cmd.sheet != "mask" && cmd.sheet != "shaded")
    throw InputError("--sheet", "expected mask or shaded, got '" + cmd.sheet + "'");
  c.shaded_sheet = cmd.sheet == "shaded";
  if (cmd.ambient) c.ambient = float(*cmd.ambient);
  if (cmd.quick) {
    if (!common.width) common.width = 320;
    if (!common.height) common.height = 240;
  }
  c.techniques = spec_list_items(cmd.techniques, "--techniques");
  c.spp = cmd.spp.value_or(cmd.quick ? 64 : 256);
  c.repeats = cmd.repeats.value_or(cmd.quick ? 3 : 5);
  c.cache_dir = cmd.no_cache ? "" : default_cache_dir();
  c.out_dir = common.out;
  c.progress = stderr_is_terminal();
  c.max_memory = max_memory_bytes(common);
}

std::vector<Scene> sweep_scenes(const SweepCommand& cmd) {
  std::vector<Scene> scenes;
  if (cmd.suite_scenes.empty()) {
    scenes.push_back(scene_from_options(cmd.common));
    return scenes;
  }
  for (const std::string& name : cmd.suite_scenes) {
    CommonOptions o = cmd.common;
    o.scene = name;
    scenes.push_back(scene_from_options(o));
  }
  return scenes;
}

void write_sweep_files(const std::string& dir, const SweepResult& r, const SweepConfig& config,
                       const std::string& plot_file) {
  write_sweep_csv(dir + "/sweep.csv", r);
  write_sweep_json(dir + "/sweep.json", r);
  if (config.shaded_sheet)
    write_png_rgb(dir + "/contact_sheet.png", sweep_contact_sheet(r, config));
  else
    write_png_grey(dir + "/contact_sheet.png", sweep_contact_sheet(r, config));
  if (!plot_file.empty())
    write_pareto_svg(plot_file, sweep_plot_points(r),
                     "resolution_sweep: " + r.scene + ", " + std::to_string(r.width) + "x" +
                         std::to_string(r.height) + ", reference " + std::to_string(config.spp) +
                         " spp");
}

}  // namespace shadowlab
