// resolution_sweep: Kluczek's Table I experiment — techniques × shadow-map resolutions against
// a ray-traced reference, every submetric plus shadow time, RP and total; CSV, JSON, masks and
// a contact sheet of them in --out; with --plot, an SVG of total and fidelity against time.
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/sweep.h"
#include "lab/sweep_command.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("resolution_sweep", "[flags]");
    SweepCommand cmd;
    add_sweep_flags(cl, cmd);
    if (!parse_command_line(cl, argc, argv)) return 0;
    finish_sweep_command(cmd);
    const CommonOptions& common = cmd.common;
    SweepConfig& c = cmd.config;
    const std::string& suite = cmd.suite;
    const std::string& plot = cmd.plot;
    const bool plot_given = cmd.plot_given;
    if (!cmd.suite_scenes.empty()) {
      // Every scene built (and its inputs checked) before the first sweep.
      const std::vector<Scene> scenes = sweep_scenes(cmd);
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
        write_sweep_files(sc.out_dir, r, sc);
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
    const Scene scene = sweep_scenes(cmd)[0];
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
    write_sweep_files(c.out_dir, r, c, plot_file);
    outputs.commit();
    std::printf("wrote %s/sweep.csv, sweep.json, contact_sheet.png and every mask and shaded image (EXR + PNG)%s%s\n",
                common.out.c_str(), plot_given ? " and plot " : "", plot.c_str());
    return 0;
  });
}
