// depth_precision: the stored-depth precision of a shadow map (techniques/pipeline/depth_quantize.h:
// float32, 16-bit, 8-bit linear, Everitt's 8-bit cubic ramp) against the ray-traced reference,
// every submetric plus time, on two scenes: the default room with its cube map, and the bunny
// under its slide projector with the projector's map. Tables on stdout; CSV, JSON and masks in
// --out/default and --out/projector.
#include <cstdio>

#include "core/error.h"
#include "core/parallel.h"
#include "scenes/scene_library.h"
#include "lab/cli.h"
#include "lab/output_folder.h"
#include "lab/sweep.h"
#include "raytrace/reference_cache.h"
#include "techniques/pipeline/depth_quantize.h"
#include "techniques/registry/technique.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("depth_precision", "[flags]");
    std::string csm_spec = "csm:res=512,pcf=3", psm_spec = "psm:res=1024,pcf=3,bias=0.002";
    int spp = 256, repeats = 5;
    bool no_cache = false;
    add_text(cl, "--csm", "SPEC", "technique on the default scene, without depth (default " + csm_spec + ")", csm_spec);
    add_text(cl, "--psm", "SPEC", "technique on the projector scene, without depth (default " + psm_spec + ")", psm_spec);
    add_int(cl, "--spp", "N", "reference samples per pixel on the default scene (default 256)", spp, 1, 1 << 20);
    add_repeats(cl, repeats, 1);
    add_switch(cl, "--no-cache", "do not read or write the reference cache", no_cache);
    CommonOptions common;
    add_common_options(cl, common);
    std::vector<std::string> unused;
    for (const std::string& n : common_scene_flags())
      if (n != "--width" && n != "--height" && n != "--out") unused.push_back(n);
    // (--max-memory is among them: the experiment's two scenes are small and fixed.)
    mark_unused(cl, unused,
                "the experiment runs the default scene and the projector scene, each with its "
                "own light and camera");
    if (!parse_command_line(cl, argc, argv)) return 0;
    const int width = common.width.value_or(1024);
    const int height = common.height.value_or(768);
    const std::string out = common.out;

    struct Case {
      const char* title;
      const char* scene;
      const char* flag;
      std::string base;
    };
    const Case cases[] = {
        {"default scene, cube map", "default", "--csm", csm_spec},
        {"bunny under the slide projector (spot), projector map", "bunny", "--psm",
         psm_spec},
    };
    // Both specs are checked before anything runs.
    for (const Case& cs : cases) {
      const TechniqueSpec spec = parse_technique_spec(cs.base, cs.flag);
      const bool projector = std::string(cs.flag) == "--psm";
      if (projector != (spec.name == "psm") || spec.name == "rt")
        throw InputError(cs.flag, projector ? "needs a psm spec (the projector scene's map)"
                                            : "needs a point-light map technique (csm, tsm, cvsm, ...)");
      if (spec.params.count("depth")) throw InputError(cs.flag, "'depth' is what this experiment sweeps");
      validate_technique(spec, cs.flag);
    }
    // Both subfolders' place checked before the first case runs.
    RunOutputs outputs(out, "--out");
    outputs.check_names({"default", "projector"}, true);
    for (const Case& cs : cases) {
      // One row per format: the spec with depth=..., at its own res.
      TechniqueSpec spec = parse_technique_spec(cs.base, cs.flag);
      if (!spec.params.count("res")) spec.params["res"] = "512";
      const int res = std::stoi(spec.params["res"]);
      spec.params.erase("res");
      SweepConfig c;
      c.techniques.clear();
      for (const std::string& f : depth_format_names()) {
        TechniqueSpec s = spec;
        s.params["depth"] = f;
        c.techniques.push_back(spec_text(s));
      }
      c.resolutions = {res};
      c.spp = spp;
      c.repeats = repeats;
      c.cache_dir = no_cache ? "" : default_cache_dir();
      const std::string sub = std::string(cs.scene) == "default" ? "default" : "projector";
      c.out_dir = outputs.subfolder(sub);
      c.progress = stderr_is_terminal();
      Scene scene = make_builtin_scene(cs.scene);
      apply_camera_size(scene, width, height);
      if (std::string(cs.scene) == "bunny") {
        Projector p = scene.projector;
        p.slide = make_slide("spot", "--psm");
        set_projector(scene, p, "--psm");
      }
      const SweepResult r = run_resolution_sweep(scene, c);
      std::printf("%s: %s %dx%d, light far %.2f m, reference %d spp, camera pass %.2f ms\n", cs.title,
                  r.scene.c_str(), r.width, r.height, double(scene.light.far), c.spp, r.camera_ms);
      std::printf("%s", sweep_table(r).c_str());
      write_sweep_csv(c.out_dir + "/sweep.csv", r);
      write_sweep_json(c.out_dir + "/sweep.json", r);
      std::printf("wrote %s/%s/sweep.csv, sweep.json and every mask\n\n", out.c_str(), sub.c_str());
    }
    outputs.commit();
    return 0;
  });
}
