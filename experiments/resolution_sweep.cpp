// resolution_sweep: Kluczek's Table I experiment — techniques × shadow-map resolutions against
// a ray-traced reference, every submetric plus shadow time, RP and total; CSV, JSON, masks and
// a contact sheet of them in --out; with --plot, an SVG of total and fidelity against time.
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/image_io.h"
#include "core/parallel.h"
#include "experiments/cli.h"
#include "experiments/sweep.h"
#include "raytrace/reference_cache.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    std::vector<FlagDef> defs = common_flags();
    defs.push_back({"--techniques", "LIST", "comma-separated technique specs without res (default: csm)"});
    defs.push_back({"--resolutions", "LIST", "shadow-map resolutions (default: 128,256,512,1024)"});
    defs.push_back({"--spp", "N", "reference samples per pixel (default 256; 1024 = the paper)"});
    defs.push_back({"--repeats", "N", "timing repeats, median reported (default 5)"});
    defs.push_back({"--quick", "", "CI size: 320x240, 64 spp, 3 repeats (explicit flags still win)"});
    defs.push_back({"--no-cache", "", "do not read or write the reference cache"});
    defs.push_back({"--plot", "FILE.svg", "also write score-vs-time plots with Pareto fronts (default: none)"});
    const ParsedArgs args = parse_args(argc, argv, defs);
    if (args.has("--help")) {
      std::printf("%s", usage_text("resolution_sweep [flags]", defs).c_str());
      return 0;
    }
    const bool quick = args.has("--quick");
    ParsedArgs a = args;
    if (quick) {
      if (!a.has("--width")) a.values["--width"] = "320";
      if (!a.has("--height")) a.values["--height"] = "240";
    }
    SweepConfig c;
    c.techniques = split_spec_list(a.get("--techniques", "csm"));
    c.resolutions = a.get_int_list("--resolutions", c.resolutions, 1, 8192);
    c.spp = a.get_int("--spp", quick ? 64 : 256, 1, 1 << 20);
    c.repeats = a.get_int("--repeats", quick ? 3 : 5, 1, 1000);
    c.cache_dir = a.has("--no-cache") ? "" : default_cache_dir();
    c.out_dir = a.get("--out", "out/resolution_sweep");
    c.progress = stderr_is_terminal();
    c.max_memory = max_memory_bytes(a);
    const Scene scene = scene_from_args(a);
    make_output_dir(c.out_dir, "--out");
    const std::string plot = a.get("--plot", "");
    // Checked before the sweep, which can take minutes, and after --out exists (the plot may go there).
    if (a.has("--plot") && plot.empty()) throw InputError("--plot", "needs a file name");
    if (!plot.empty() && !std::filesystem::is_directory(std::filesystem::absolute(plot).parent_path()))
      throw InputError("--plot", "'" + plot + "': folder does not exist");
    if (!plot.empty() && std::filesystem::is_directory(plot))
      throw InputError("--plot", "'" + plot + "' is a folder; give a file name such as plot.svg");
    const SweepResult r = run_resolution_sweep(scene, c);
    std::printf("scene %s, %dx%d, light radius %.3f m, reference %d spp, %d threads, camera pass %.2f ms\n",
                r.scene.c_str(), r.width, r.height, scene.light.radius, c.spp, thread_count(),
                r.camera_ms);
    std::printf("%s", sweep_table(r).c_str());
    for (const SweepRow& row : r.rows)
      std::printf("  %-16s %s\n", row.label.c_str(), row.result.notes.c_str());
    std::printf("  reference: %s\n", r.reference.result.notes.c_str());
    write_sweep_csv(c.out_dir + "/sweep.csv", r);
    write_sweep_json(c.out_dir + "/sweep.json", r);
    std::printf("wrote %s/sweep.csv, sweep.json and every mask (EXR + PNG)\n", c.out_dir.c_str());
    write_png_grey(c.out_dir + "/contact_sheet.png", sweep_contact_sheet(r, c));
    if (!plot.empty())
      write_pareto_svg(plot, sweep_plot_points(r),
                       "resolution_sweep: " + r.scene + ", " + std::to_string(r.width) + "x" +
                           std::to_string(r.height) + ", reference " + std::to_string(c.spp) + " spp");
    std::printf("wrote %s/contact_sheet.png%s%s\n", c.out_dir.c_str(),
                plot.empty() ? "" : " and plot ", plot.c_str());
    return 0;
  });
}
