// resolution_sweep: Kluczek's Table I experiment — techniques × shadow-map resolutions against
// a ray-traced reference, every submetric plus shadow time, RP and total; CSV, JSON, masks and
// a contact sheet of them in --out; with --plot, an SVG of total and fidelity against time.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/error.h"
#include "core/image_io.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/sweep.h"
#include "raytrace/reference_cache.h"
#include "scenes/scene_registry.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("resolution_sweep", "[flags]");
    CommonOptions common;
    add_common_options(cl, common);
    SweepConfig c;
    std::string techniques = "csm";
    std::optional<int> spp, repeats_given;
    bool quick = false, no_cache = false, plot_given = false;
    std::string plot;
    add_text(cl, "--techniques", "LIST", "comma-separated light-map technique specs without res (the ray tracer is the reference: --spp) (default: csm)", techniques);
    add_int_list(cl, "--resolutions", "LIST", "shadow-map resolutions (default: 128,256,512,1024)", c.resolutions, 1, 8192);
    add_int(cl, "--spp", "N", "reference samples per pixel (default 256; 1024 = the paper)", spp, 1, 1 << 20);
    add_int(cl, "--repeats", "N", "timed runs, the median reported (default 5; 3 with --quick)", repeats_given, 1, 100000);
    add_switch(cl, "--quick", "CI size: 320x240, 64 spp, 3 repeats (explicit flags still win)", quick);
    add_switch(cl, "--no-cache", "do not read or write the reference cache", no_cache);
    add_text(cl, "--plot", "FILE.svg", "also write score-vs-time plots with Pareto fronts (default: none)", plot, &plot_given);
    std::string sheet = "mask";
    std::optional<double> ambient;
    add_text(cl, "--sheet", "KIND", "contact sheet of masks or shaded images: mask or shaded (default mask)", sheet);
    add_double(cl, "--ambient", "A", "ambient level of the shaded images, [0, 1] (default 0.1)", ambient, 0.0, 1.0);
    add_switch(cl, "--flip-map", "also write each row's LDR-FLIP error map of its shaded image against the reference's (PREFIX_flip.exr, .png)", c.flip_map);
    std::string suite;
    add_text(cl, "--suite", "NAME", "run every scene of a suite (hard: grazing, contact, depth_range, cluttered; all: those + default, foliage, bunny) instead of --scene: a table per scene in --out/SCENE/, then each setting's fidelity and total per scene with the mean and the worst (default: none)", suite);
    std::string shard;
    add_text(cl, "--shard", "i/N", "run only the rows (technique x resolution, in order) with index mod N == i, writing sweep_shardIofN.csv/.json; combine with build/programs/merge (default 0/1)", shard);
    if (!parse_command_line(cl, argc, argv)) return 0;
    if (!shard.empty()) parse_shard(shard, c.shard, c.shards);
    std::vector<std::string> suite_scenes;
    if (!suite.empty()) {
      suite_scenes = scene_suite(suite, "--suite");
      reject_scene_with_suite(common);
      if (!plot.empty() || plot_given) throw InputError("--plot", "is per scene; not with --suite");
      if (c.shards > 1) throw InputError("--shard", "not with --suite (shard each scene's sweep instead)");
    }
    if (sheet != "mask" && sheet != "shaded")
      throw InputError("--sheet", "expected mask or shaded, got '" + sheet + "'");
    c.shaded_sheet = sheet == "shaded";
    if (ambient) c.ambient = float(*ambient);
    if (quick) {
      if (!common.width) common.width = 320;
      if (!common.height) common.height = 240;
    }
    c.techniques = spec_list_items(techniques, "--techniques");
    c.spp = spp.value_or(quick ? 64 : 256);
    c.repeats = repeats_given.value_or(quick ? 3 : 5);
    c.cache_dir = no_cache ? "" : default_cache_dir();
    c.out_dir = common.out;
    c.progress = stderr_is_terminal();
    c.max_memory = max_memory_bytes(common);
    if (!suite_scenes.empty()) {
      // Every scene built (and its inputs checked) before the first sweep.
      std::vector<Scene> scenes;
      for (const std::string& name : suite_scenes) {
        CommonOptions o = common;
        o.scene = name;
        scenes.push_back(scene_from_options(o));
      }
      RunOutputs outputs(common.out, "--out");
      outputs.check_names({"sweep.csv", "sweep.json"});
      {
        std::vector<std::string> names;
        for (const Scene& scene : scenes) names.push_back(scene.name);
        outputs.check_names(names, true);
      }
      c.out_dir = outputs.dir();
      std::vector<SweepResult> results;
      for (const Scene& scene : scenes) {
        SweepConfig sc = c;
        sc.out_dir = outputs.subfolder(scene.name);
        results.push_back(run_resolution_sweep(scene, sc));
        const SweepResult& r = results.back();
        std::printf("scene %s, %dx%d, light radius %.3f m, reference %d spp, %d threads, camera pass %.2f ms\n",
                    r.scene.c_str(), r.width, r.height, scene.light.radius, c.spp, thread_count(),
                    r.camera_ms);
        std::printf("%s\n", sweep_table(r).c_str());
        write_sweep_csv(sc.out_dir + "/sweep.csv", r);
        write_sweep_json(sc.out_dir + "/sweep.json", r);
        if (c.shaded_sheet)
          write_png_rgb(sc.out_dir + "/contact_sheet.png", sweep_contact_sheet(r, sc));
        else
          write_png_grey(sc.out_dir + "/contact_sheet.png", sweep_contact_sheet(r, sc));
      }
      std::printf("suite %s: %zu scenes\n%s", suite.c_str(), results.size(), suite_table(results).c_str());
      std::vector<const SweepResult*> all;
      for (const SweepResult& r : results) all.push_back(&r);
      write_sweep_csv(c.out_dir + "/sweep.csv", all);
      nlohmann::json j;
      j["suite"] = suite;
      j["scenes"] = nlohmann::json::array();
      for (const SweepResult& r : results) j["scenes"].push_back(sweep_json(r));
      write_text_file(c.out_dir + "/sweep.json", j.dump(2) + "\n");
      outputs.commit();
      std::printf("wrote %s/sweep.csv, sweep.json (every scene, with a scene column) and per scene "
                  "SCENE/sweep.csv, sweep.json, contact_sheet.png and every mask and shaded image\n",
                  common.out.c_str());
      return 0;
    }
    const Scene scene = scene_from_options(common);
    if (c.shards > 1 && plot_given) throw InputError("--plot", "not with --shard: merge draws the plot");
    // Checked before the sweep, which can take minutes. A shard adds its files to the folder
    // the other shards write into.
    RunOutputs outputs(common.out, "--out", c.shards > 1);
    if (c.shards > 1) {
      const std::string stem = "sweep_shard" + std::to_string(c.shard) + "of" + std::to_string(c.shards);
      outputs.check_names({stem + ".csv", stem + ".json"});
    } else {
      outputs.check_names({"sweep.csv", "sweep.json", "contact_sheet.png"});
    }
    const std::string plot_file = plot_given ? outputs.file("--plot", plot, ".svg") : std::string();
    c.out_dir = outputs.dir();
    const SweepResult r = run_resolution_sweep(scene, c);
    if (c.shards > 1) {
      const std::string stem = c.out_dir + "/sweep_shard" + std::to_string(c.shard) + "of" + std::to_string(c.shards);
      write_sweep_csv(stem + ".csv", r);
      write_sweep_json(stem + ".json", r);
      outputs.commit();
      std::printf("shard %d/%d: %zu of %zu rows; wrote %s/sweep_shard%dof%d.csv, .json and the rows' masks and shaded images\n",
                  c.shard, c.shards, r.rows.size(), r.rows_total, common.out.c_str(), c.shard, c.shards);
      return 0;
    }
    std::printf("scene %s, %dx%d, light radius %.3f m, reference %d spp, %d threads, camera pass %.2f ms\n",
                r.scene.c_str(), r.width, r.height, scene.light.radius, c.spp, thread_count(),
                r.camera_ms);
    std::printf("%s", sweep_table(r).c_str());
    for (const SweepRow& row : r.rows)
      std::printf("  %-16s %s\n", row.label.c_str(), row.result.notes.c_str());
    std::printf("  reference: %s\n", r.reference.result.notes.c_str());
    write_sweep_csv(c.out_dir + "/sweep.csv", r);
    write_sweep_json(c.out_dir + "/sweep.json", r);
    if (c.shaded_sheet)
      write_png_rgb(c.out_dir + "/contact_sheet.png", sweep_contact_sheet(r, c));
    else
      write_png_grey(c.out_dir + "/contact_sheet.png", sweep_contact_sheet(r, c));
    if (plot_given)
      write_pareto_svg(plot_file, sweep_plot_points(r),
                       "resolution_sweep: " + r.scene + ", " + std::to_string(r.width) + "x" +
                           std::to_string(r.height) + ", reference " + std::to_string(c.spp) + " spp");
    outputs.commit();
    std::printf("wrote %s/sweep.csv, sweep.json, contact_sheet.png and every mask and shaded image (EXR + PNG)%s%s\n",
                common.out.c_str(), plot_given ? " and plot " : "", plot.c_str());
    return 0;
  });
}
