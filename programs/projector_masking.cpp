// projector_masking: Dowling's slide-projector experiment with numbers — the bunny at 69k, 5k,
// 1k and 300 triangles under four slides; every level's shaded image against the full mesh's
// under the same slide. Prints the tables; writes masking.csv, contact_sheet.png (the layout
// of the paper's Figures 6–9) and every shaded PNG into --out.
#include <cstdio>

#include "core/error.h"
#include "core/image_io.h"
#include "core/parallel.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/lod_masking.h"
#include "raytrace/reference_cache.h"
#include "techniques/registry/technique_spec.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("projector_masking", "[flags]");
    CommonOptions common;
    add_common_options(cl, common);
    mark_unused(cl, {"--scene"}, "the experiment is the bunny's, the scene of the paper");
    mark_unused(cl, {"--slide"}, "it takes --slides, a list");
    mark_unused(cl, {"--light-radius"}, "a slide projector is a point source");
    mark_unused(cl, {"--max-memory"}, "its images are the bunny's at the given size; no estimate is made");
    MaskingConfig c;
    std::vector<int> level_list = {5000, 1000, 300};
    std::string slides;
    bool slides_given = false, no_cache = false;
    double ambient = c.ambient;
    int sheet_cell = 256;
    add_int_list(cl, "--levels", "LIST", "target triangle counts (default 5000,1000,300; the full mesh is always the reference)", level_list, 1, 100000000);
    add_text(cl, "--slides", "LIST", "slides separated by ';' (default: the paper's four grids)", slides, &slides_given);
    add_text(cl, "--technique", "SPEC", "visibility technique (default " + c.technique + "; rt:hard=1 for ray-traced)", c.technique);
    add_double(cl, "--ambient", "A", "ambient level of the shaded images, [0, 1] (default 0.1)", ambient, 0.0, 1.0);
    add_repeats(cl, c.repeats, 1);
    add_switch(cl, "--no-cache", "do not read or write the LOD / reference cache", no_cache);
    add_int(cl, "--sheet-cell", "PX", "contact sheet cells at most PX wide (default 256)", sheet_cell, 16, 4096);
    if (!parse_command_line(cl, argc, argv)) return 0;
    std::vector<size_t> levels = {0};
    for (int t : level_list) levels.push_back(size_t(t));
    c.levels = levels;
    if (slides_given) c.slides = split(slides, ';');
    c.ambient = float(ambient);
    c.cache_dir = no_cache ? "" : default_cache_dir();
    c.out_dir = common.out;
    common.scene = "bunny";
    const Scene scene = scene_from_options(common);
    RunOutputs outputs(c.out_dir, "--out");
    outputs.check_names({"masking.csv", "contact_sheet.png"});
    c.out_dir = outputs.dir();
    const MaskingResult r = run_lod_masking(scene, c);
    std::printf("projector_masking: bunny %dx%d, visibility %s, ambient %.2f, %d threads\n",
                r.width, r.height, c.technique.c_str(), double(c.ambient), thread_count());
    std::printf("%s", masking_tables(r).c_str());
    write_masking_csv(c.out_dir + "/masking.csv", r);
    write_png_grey(c.out_dir + "/contact_sheet.png", masking_contact_sheet(r, sheet_cell));
    outputs.commit();
    std::printf("wrote %s/masking.csv, contact_sheet.png and every shaded image\n", common.out.c_str());
    return 0;
  });
}
