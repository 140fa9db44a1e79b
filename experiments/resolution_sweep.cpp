// resolution_sweep: Kluczek's Table I experiment — techniques × shadow-map resolutions against
// a ray-traced reference, every submetric plus shadow time, RP and total; CSV, JSON, masks and
// a contact sheet of them in --out; with --plot, an SVG of total and fidelity against time.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/error.h"
#include "core/image_io.h"
#include "core/parallel.h"
#include "experiments/cli.h"
#include "experiments/sweep.h"
#include "raytrace/reference_cache.h"

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
    add_text(cl, "--techniques", "LIST", "comma-separated technique specs without res (default: csm)", techniques);
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
    if (!parse_command_line(cl, argc, argv)) return 0;
    if (sheet != "mask" && sheet != "shaded")
      throw InputError("--sheet", "expected mask or shaded, got '" + sheet + "'");
    c.shaded_sheet = sheet == "shaded";
    if (ambient) c.ambient = float(*ambient);
    if (quick) {
      if (!common.width) common.width = 320;
      if (!common.height) common.height = 240;
    }
    c.techniques = split_spec_list(techniques);
    c.spp = spp.value_or(quick ? 64 : 256);
    c.repeats = repeats_given.value_or(quick ? 3 : 5);
    c.cache_dir = no_cache ? "" : default_cache_dir();
    c.out_dir = common.out;
    c.progress = stderr_is_terminal();
    c.max_memory = max_memory_bytes(common);
    const Scene scene = scene_from_options(common);
    make_output_dir(c.out_dir, "--out");
    // Checked before the sweep, which can take minutes, and after --out exists (the plot may go there).
    if (plot_given && plot.empty()) throw InputError("--plot", "needs a file name");
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
    std::printf("wrote %s/sweep.csv, sweep.json and every mask and shaded image (EXR + PNG)\n", c.out_dir.c_str());
    if (c.shaded_sheet)
      write_png_rgb(c.out_dir + "/contact_sheet.png", sweep_contact_sheet(r, c));
    else
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
