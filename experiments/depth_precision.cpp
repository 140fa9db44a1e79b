// depth_precision: the stored-depth precision of a shadow map (techniques/depth_quantize.h:
// float32, 16-bit, 8-bit linear, Everitt's 8-bit cubic ramp) against the ray-traced reference,
// every submetric plus time, on two scenes: the default room with its cube map, and the bunny
// under its slide projector with the projector's map. Tables on stdout; CSV, JSON and masks in
// --out/default and --out/projector.
#include <cstdio>

#include "core/error.h"
#include "core/parallel.h"
#include "core/scene_library.h"
#include "experiments/cli.h"
#include "experiments/sweep.h"
#include "raytrace/reference_cache.h"
#include "techniques/depth_quantize.h"
#include "techniques/technique.h"

using namespace shadowlab;

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    std::vector<FlagDef> defs = {
        {"--csm", "SPEC", "technique on the default scene, without depth (default csm:res=512,pcf=3)"},
        {"--psm", "SPEC", "technique on the projector scene, without depth (default psm:res=1024,pcf=3,bias=0.002)"},
        {"--spp", "N", "reference samples per pixel on the default scene (default 256)"},
        {"--repeats", "N", "timing repeats, median reported (default 5)"},
        {"--no-cache", "", "do not read or write the reference cache"},
    };
    for (FlagDef d : common_flags()) {
      if (d.name == "--width") d.help = "image width (default 1024)";
      if (d.name == "--height") d.help = "image height (default 768)";
      if (d.name == "--out") d.help = "output folder (default out/depth_precision)";
      defs.push_back(d);
    }
    std::vector<std::string> unused;
    for (const std::string& n : common_scene_flags())
      if (n != "--width" && n != "--height" && n != "--out") unused.push_back(n);
    // (--max-memory is among them: the experiment's two scenes are small and fixed.)
    mark_unused(defs, unused,
                "the experiment runs the default scene and the projector scene, each with its "
                "own light and camera");
    const ParsedArgs args = parse_args(argc, argv, defs);
    if (args.has("--help")) {
      std::printf("%s", usage_text("depth_precision [flags]", defs).c_str());
      return 0;
    }
    if (args.has("--threads")) set_thread_count(args.get_int("--threads", 1, 1, 1024));
    const int width = args.get_int("--width", 1024, 1, kMaxImageSide);
    const int height = args.get_int("--height", 768, 1, kMaxImageSide);
    const std::string out = args.get("--out", "out/depth_precision");

    struct Case {
      const char* title;
      const char* scene;
      const char* flag;
      std::string base;
    };
    const Case cases[] = {
        {"default scene, cube map", "default", "--csm", args.get("--csm", "csm:res=512,pcf=3")},
        {"bunny under the slide projector (spot), projector map", "bunny", "--psm",
         args.get("--psm", "psm:res=1024,pcf=3,bias=0.002")},
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
      c.spp = args.get_int("--spp", 256, 1, 1 << 20);
      c.repeats = args.get_int("--repeats", 5, 1, 1000);
      c.cache_dir = args.has("--no-cache") ? "" : default_cache_dir();
      c.out_dir = out + "/" + (std::string(cs.scene) == "default" ? "default" : "projector");
      c.progress = stderr_is_terminal();
      Scene scene = make_builtin_scene(cs.scene);
      apply_camera_size(scene, width, height);
      if (std::string(cs.scene) == "bunny") {
        Projector p = scene.projector;
        p.slide = make_slide("spot", "--psm");
        set_projector(scene, p, "--psm");
      }
      make_output_dir(c.out_dir, "--out");
      const SweepResult r = run_resolution_sweep(scene, c);
      std::printf("%s: %s %dx%d, light far %.2f m, reference %d spp, camera pass %.2f ms\n", cs.title,
                  r.scene.c_str(), r.width, r.height, double(scene.light.far), c.spp, r.camera_ms);
      std::printf("%s", sweep_table(r).c_str());
      write_sweep_csv(c.out_dir + "/sweep.csv", r);
      write_sweep_json(c.out_dir + "/sweep.json", r);
      std::printf("wrote %s/sweep.csv, sweep.json and every mask\n\n", c.out_dir.c_str());
    }
    return 0;
  });
}
