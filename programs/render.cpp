// render: one technique on one scene → mask.exr, mask.png, texel.exr, timing.json and the shaded
// image shaded.exr (linear) and shaded.png (sRGB) (techniques/shading/scene_shading.h).
#include <chrono>
#include <cstdio>
#include <optional>

#include "core/image_io.h"
#include "core/timer.h"
#include "lab/view_check.h"
#include "lab/cli.h"
#include "lab/provenance.h"
#include "lab/memory_check.h"
#include "lab/output_files.h"
#include "lab/output_folder.h"
#include "techniques/shading/scene_shading.h"
#include "raster/gbuffer_pass.h"
#include "raytrace/reference_cache.h"
#include "techniques/rt/rt_denoised.h"
#include "techniques/shading/projector_shading.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("render", "--technique SPEC [--out DIR] [flags]");
    CommonOptions common;
    add_common_options(cl, common);
    std::string technique;
    int repeats = 5;
    bool no_cache = false;
    ProjectorShading shading;
    std::optional<double> ambient;
    add_text(cl, "--technique", "SPEC", "technique spec, e.g. csm:res=1024,pcf=3 or rt:spp=256 (required)", technique);
    add_repeats(cl, repeats, 1);
    add_switch(cl, "--no-cache", "do not read or write the reference cache", no_cache);
    add_double(cl, "--ambient", "A", "ambient level of the shaded image, [0, 1] (default 0.1)", ambient, 0.0, 1.0);
    if (!parse_command_line(cl, argc, argv)) return 0;
    if (technique.empty()) throw InputError("--technique", "is required (see --help)");
    const TechniqueSpec spec = parse_technique_spec(technique, "--technique");
    validate_technique(spec, "--technique");
    if (ambient) shading.ambient = float(*ambient);
    const Scene scene = scene_from_options(common);
    validate_technique_for_scene(spec, scene, "--technique");
    check_run_memory(scene, {spec}, max_memory_bytes(common));
    const std::string& out = common.out;
    RunOutputs outputs(out, "--out");
    outputs.check_names({"mask.exr", "mask.png", "texel.exr", "timing.json", "shaded.exr", "shaded.png"});

    GBuffer g;
    const double camera_ms = median_ms(repeats, [&] { render_gbuffer(scene, g); });
    require_covered_view(scene, g);
    RunOptions opt;
    opt.repeats = repeats;
    opt.cache_dir = no_cache ? "" : default_cache_dir();
    opt.progress = stderr_is_terminal();
    const ShadowResult r = run_technique(spec, scene, g, opt);
    const ImageF shaded = shade_scene(scene, g, r.mask, shading.ambient);
    write_result_files(outputs.dir(), "", r, spec.text, camera_ms, provenance_json({&scene}, 0, repeats), &shaded);
    outputs.commit();
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
    if (r.network_ms > 0.0)
      std::printf("network: features %.3f ms + forward %.3f ms; %.3g multiply-adds, %.2f MB of "
                  "activations\n",
                  r.features_ms, r.network_ms, double(w.multiply_adds),
                  double(w.activation_bytes) * 1e-6);
    if (w.rays > 0)
      std::printf("rays: %llu cast in %.3f ms (%.1f M rays/s); denoiser %.3f ms, %llu filter taps\n",
                  (unsigned long long)w.rays, r.rays_ms, mrays_per_second(w.rays, r.rays_ms),
                  r.denoise_ms, (unsigned long long)w.filter_taps);
    std::printf("wrote %s/mask.exr, mask.png%s, timing.json, shaded.exr, shaded.png\n", out.c_str(),
                r.texels.empty() ? "" : ", texel.exr");
    return 0;
  });
}
