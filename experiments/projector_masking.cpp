// projector_masking: Dowling's slide-projector experiment with numbers — the bunny at 69k, 5k,
// 1k and 300 triangles under four slides; every level's shaded image against the full mesh's
// under the same slide. Prints the tables; writes masking.csv, contact_sheet.png (the layout
// of the paper's Figures 6–9) and every shaded PNG into --out.
#include <cstdio>

#include "core/error.h"
#include "core/image_io.h"
#include "core/parallel.h"
#include "experiments/cli.h"
#include "experiments/lod_masking.h"
#include "raytrace/reference_cache.h"
#include "techniques/technique_spec.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    std::vector<FlagDef> defs = common_flags();
    mark_unused(defs, {"--scene"}, "the experiment is the bunny's, the scene of the paper");
    mark_unused(defs, {"--slide"}, "it takes --slides, a list");
    mark_unused(defs, {"--light-radius"}, "a slide projector is a point source");
    mark_unused(defs, {"--max-memory"}, "its images are the bunny's at the given size; no estimate is made");
    defs.push_back({"--levels", "LIST", "target triangle counts (default 5000,1000,300; the full mesh is always the reference)"});
    defs.push_back({"--slides", "LIST", "slides separated by ';' (default: the paper's four grids)"});
    defs.push_back({"--technique", "SPEC", "visibility technique (default psm:res=2048,pcf=3; rt:hard=1 for ray-traced)"});
    defs.push_back({"--ambient", "A", "ambient level of the shaded images, [0, 1] (default 0.1)"});
    defs.push_back({"--repeats", "N", "timing repeats, median reported (default 3)"});
    defs.push_back({"--no-cache", "", "do not read or write the LOD / reference cache"});
    defs.push_back({"--sheet-cell", "PX", "contact sheet cells at most PX wide (default 256)"});
    const ParsedArgs args = parse_args(argc, argv, defs);
    if (args.has("--help")) {
      std::printf("%s", usage_text("projector_masking [flags]", defs).c_str());
      return 0;
    }
    ParsedArgs a = args;
    a.values["--scene"] = "bunny";
    MaskingConfig c;
    std::vector<size_t> levels = {0};
    for (int t : a.get_int_list("--levels", {5000, 1000, 300}, 1, 100000000)) levels.push_back(size_t(t));
    c.levels = levels;
    if (a.has("--slides")) c.slides = split(a.get("--slides", ""), ';');
    c.technique = a.get("--technique", c.technique);
    c.ambient = float(a.get_double("--ambient", c.ambient, 0.0, 1.0));
    c.repeats = a.get_int("--repeats", c.repeats, 1, 1000);
    c.cache_dir = a.has("--no-cache") ? "" : default_cache_dir();
    c.out_dir = a.get("--out", "out/projector_masking");
    const int sheet_cell = a.get_int("--sheet-cell", 256, 16, 4096);
    const Scene scene = scene_from_args(a);
    make_output_dir(c.out_dir, "--out");
    const MaskingResult r = run_lod_masking(scene, c);
    std::printf("projector_masking: bunny %dx%d, visibility %s, ambient %.2f, %d threads\n",
                r.width, r.height, c.technique.c_str(), double(c.ambient), thread_count());
    std::printf("%s", masking_tables(r).c_str());
    write_masking_csv(c.out_dir + "/masking.csv", r);
    write_png_grey(c.out_dir + "/contact_sheet.png", masking_contact_sheet(r, sheet_cell));
    std::printf("wrote %s/masking.csv, contact_sheet.png and every shaded image\n", c.out_dir.c_str());
    return 0;
  });
}
