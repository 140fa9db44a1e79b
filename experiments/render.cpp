// render: one technique on one scene → mask.exr, mask.png, texel.exr, timing.json; with a
// slide projector (--slide) also the shaded image shaded.exr (linear) and shaded.png (sRGB).
#include <chrono>
#include <cstdio>

#include "core/image_io.h"
#include "core/timer.h"
#include "experiments/cli.h"
#include "experiments/memory_check.h"
#include "experiments/output_files.h"
#include "raster/gbuffer_pass.h"
#include "raytrace/reference_cache.h"
#include "techniques/projector_shading.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    std::vector<FlagDef> defs = common_flags();
    defs.push_back({"--technique", "SPEC", "technique spec, e.g. csm:res=1024,pcf=3 or rt:spp=256 (required)"});
    defs.push_back({"--repeats", "N", "timing repeats, median reported (default 5)"});
    defs.push_back({"--no-cache", "", "do not read or write the reference cache"});
    defs.push_back({"--ambient", "A", "projector scenes: ambient level of the shaded image, [0, 1] (default 0.1)"});
    const ParsedArgs args = parse_args(argc, argv, defs);
    if (args.has("--help")) {
      std::printf("%s", usage_text("render --technique SPEC [--out DIR] [flags]", defs).c_str());
      return 0;
    }
    if (!args.has("--technique")) throw InputError("--technique", "is required (see --help)");
    const TechniqueSpec spec = parse_technique_spec(args.get("--technique", ""), "--technique");
    validate_technique(spec, "--technique");
    const int repeats = args.get_int("--repeats", 5, 1, 1000);
    ProjectorShading shading;
    shading.ambient = float(args.get_double("--ambient", shading.ambient, 0.0, 1.0));
    const Scene scene = scene_from_args(args);
    if (args.has("--ambient") && !scene.projector.enabled)
      throw InputError("--ambient", "needs --slide (only projector scenes are shaded)");
    validate_technique_for_scene(spec, scene, "--technique");
    check_run_memory(scene, {spec}, max_memory_bytes(args));
    const std::string out = args.get("--out", "out/render");
    make_output_dir(out, "--out");

    GBuffer g;
    const double camera_ms = median_ms(repeats, [&] { render_gbuffer(scene, g); });
    RunOptions opt;
    opt.repeats = repeats;
    opt.cache_dir = args.has("--no-cache") ? "" : default_cache_dir();
    opt.progress = stderr_is_terminal();
    const ShadowResult r = run_technique(spec, scene, g, opt);
    write_result_files(out, "", r, spec.text, camera_ms);
    if (scene.projector.enabled) {
      const ImageF shaded = shade_projector(scene, g, r.mask, shading);
      write_exr_rgb(out + "/shaded.exr", shaded);
      write_png_rgb(out + "/shaded.png", shaded);
    }
    std::printf("%s on %s %dx%d: shadow %.3f ms (map %.3f = faces %.3f + render %.3f + filter %.3f;"
                " lookup %.3f), camera pass %.3f ms; %s\n",
                spec.text.c_str(), scene.name.c_str(), g.width, g.height, r.shadow_ms(), r.map_ms,
                r.faces_ms, r.render_ms, r.filter_ms, r.lookup_ms, camera_ms, r.notes.c_str());
    const WorkCounts& w = r.work;
    std::printf("work: %llu triangles submitted, %llu binned; %llu texels rendered, %llu filtered; "
                "%llu pixels looked up, %.2f taps/pixel; %.2f MB written, %.2f MB read\n",
                (unsigned long long)w.triangles_submitted, (unsigned long long)w.triangles_binned,
                (unsigned long long)w.texels_rendered, (unsigned long long)w.texels_filtered,
                (unsigned long long)w.pixels_looked_up, w.taps_per_pixel(),
                double(w.bytes_written) * 1e-6, double(w.bytes_read) * 1e-6);
    std::printf("wrote %s/mask.exr, mask.png%s, timing.json%s\n", out.c_str(),
                r.texels.empty() ? "" : ", texel.exr",
                scene.projector.enabled ? ", shaded.exr, shaded.png" : "");
    return 0;
  });
}
