// nsm_data: the Neural Shadow Mapping data set (docs/programs/nsm_data.md): frames along camera
// and light trajectories over built-in scenes, each a crop window of its features, of 3
// perturbed copies' features and of the ray-traced reference at every light radius, one .nsmf
// file per frame in --out/frames/, and --out/manifest.json with the splits and the data set hash.
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parse_number.h"
#include "lab/cli.h"
#include "lab/nsm_dataset.h"
#include "lab/output_folder.h"
#include "lab/provenance.h"
#include "techniques/nsm/nsm_features.h"

using namespace shadowlab;

namespace {

// "W,H", each in [8, 4096].
void parse_crop(const std::string& text, NsmDatasetParams& p) {
  const std::vector<std::string> parts = split(text, ',');
  long w = 0, h = 0;
  if (parts.size() != 2 || !parse_long(parts[0], w) || !parse_long(parts[1], h))
    throw InputError("--crop", "expected W,H (two integers), got '" + text + "'");
  if (w < 8 || h < 8 || w > 4096 || h > 4096)
    throw InputError("--crop", "each side must lie in [8, 4096], got '" + text + "'");
  p.crop_w = int(w);
  p.crop_h = int(h);
}

// A fraction in [0, 1], or a comma-separated list of scene names.
NsmSplit parse_split(const std::string& text, const char* flag) {
  NsmSplit s;
  double f = 0.0;
  if (parse_double(text, f)) {
    if (!(f >= 0.0 && f <= 1.0)) throw InputError(flag, "a fraction must lie in [0, 1], got '" + text + "'");
    s.fraction = f;
    return s;
  }
  for (const std::string& n : split(text, ',')) {
    if (n.empty()) throw InputError(flag, "empty scene name in '" + text + "'");
    s.scenes.push_back(n);
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  return run_main(argc, argv, [](int argc, char** argv) {
    CommandLine cl = make_command_line("nsm_data", "[--scenes LIST] [--frames N] [--out DIR] [flags]");
    CommonOptions common;
    add_common_options(cl, common);
    set_default_size(cl, common, 1024, 768, "the full frame, the inference resolution");
    std::vector<std::string> unused;
    for (const std::string& n : common_scene_flags())
      if (n != "--out" && n != "--width" && n != "--height" && n != "--max-memory") unused.push_back(n);
    mark_unused(cl, unused, "the frames' scenes are --scenes, their views and lights the trajectories");
    mark_unused(cl, {"--max-memory"}, "a frame's memory is bounded by the flags' ranges (--width, --height <= 4096, --base-res <= 4096: about 1 GB)");
    NsmDatasetParams p;
    std::string scenes = "default", crop = "256,192", val = "0.1", test = "0.1", features = "all";
    int seed = 1;
    add_text(cl, "--scenes", "LIST", "built-in scenes, comma-separated; frame i uses scene i mod count (default default)", scenes);
    add_int(cl, "--frames", "N", "frames (default 16)", p.frames, 1, 1000000);
    add_text(cl, "--crop", "W,H", "the stored window, placed from each frame's seed (default 256,192)", crop);
    add_double_list(cl, "--radii", "LIST", "light radii of the reference planes, metres (default 0,0.075,0.15,0.225,0.3)", p.radii, 0.0, 1.0);
    add_int(cl, "--spp", "N", "reference samples per pixel of the soft radii (default 256)", p.spp, 1, 65536);
    add_int(cl, "--base-res", "N", "the base map's cube face edge, texels (default 1024)", p.base_res, 16, 4096);
    add_int(cl, "--seed", "N", "seed of the trajectories, crops, perturbations and reference samples (default 1)", seed, 0, 2147483647);
    add_text(cl, "--features", "LIST", "stored features, comma-separated (all: every candidate; net: z_over_zf,z_minus_zf,c_e_r,d) (default all)", features);
    add_text(cl, "--split-val", "F|LIST", "validation frames: a fraction in [0, 1] or a list of scenes (default 0.1)", val);
    add_text(cl, "--split-test", "F|LIST", "test frames: a fraction in [0, 1] or a list of scenes held out, e.g. bunny (default 0.1)", test);
    if (!parse_command_line(cl, argc, argv)) return 0;
    p.width = common.width.value_or(1024);
    p.height = common.height.value_or(768);
    if (p.width > 4096 || p.height > 4096)
      throw InputError(p.width > 4096 ? "--width" : "--height", "the frame's sides must be at most 4096");
    p.seed = uint64_t(seed);
    parse_crop(crop, p);
    p.scenes.clear();
    for (const std::string& n : split(scenes, ',')) {
      if (n.empty()) throw InputError("--scenes", "empty scene name in '" + scenes + "'");
      p.scenes.push_back(n);
    }
    p.val = parse_split(val, "--split-val");
    p.test = parse_split(test, "--split-test");
    if (features == "net") {
      p.features = nsm_network_features();
    } else if (features != "all") {
      for (const std::string& n : split(features, ',')) p.features.push_back(n);
    }
    check_nsm_dataset_params(p);
    RunOutputs outputs(common.out, "--out");
    outputs.check_names({"manifest.json"});
    outputs.check_names({"frames"}, true);
    const std::vector<std::string> command =
        command_without(run_arguments(), {"--threads", "--out"});
    const uint64_t hash = write_nsm_dataset(p, outputs.dir(), command, stderr_is_terminal());
    outputs.commit();
    std::printf("wrote %d frames of %dx%d (%zu features x 4 copies, %zu reference planes) to %s/, "
                "data set hash %016llx\n",
                p.frames, p.crop_w, p.crop_h, p.features.size(), p.radii.size(), common.out.c_str(),
                static_cast<unsigned long long>(hash));
    return 0;
  });
}
