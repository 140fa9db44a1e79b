#include "lab/nsm_data_command.h"

#include <vector>

#include "core/error.h"
#include "core/parse_number.h"
#include "techniques/nsm/nsm_features.h"

namespace shadowlab {

namespace {

// "W,H", each in [8, 4096].
void nsm_parse_crop(const std::string& text, NsmDatasetParams& p) {
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
NsmSplit nsm_parse_split(const std::string& text, const char* flag) {
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

void add_nsm_data_flags(CommandLine& cl, NsmDataCommand& cmd) {
  add_common_options(cl, cmd.common);
  set_default_size(cl, cmd.common, 1024, 768, "the full frame, the inference resolution");
  std::vector<std::string> unused;
  for (const std::string& n : common_scene_flags())
    if (n != "--out" && n != "--width" && n != "--height" && n != "--max-memory") unused.push_back(n);
  mark_unused(cl, unused, "the frames' scenes are --scenes, their views and lights the trajectories");
  mark_unused(cl, {"--max-memory"}, "a frame's memory is bounded by the flags' ranges (--width, --height <= 4096, --base-res <= 4096: about 1 GB)");
  add_text(cl, "--scenes", "LIST", "built-in scenes, comma-separated; frame i uses scene i mod count (default default)", cmd.scenes);
  add_int(cl, "--frames", "N", "frames (default 16)", cmd.params.frames, 1, 1000000);
  add_text(cl, "--crop", "W,H", "the stored window, placed from each frame's seed (default 256,192)", cmd.crop);
  add_double_list(cl, "--radii", "LIST", "light radii of the reference planes, metres (default 0,0.075,0.15,0.225,0.3)", cmd.params.radii, 0.0, 1.0);
  add_int(cl, "--spp", "N", "reference samples per pixel of the soft radii (default 256)", cmd.params.spp, 1, 65536);
  add_int(cl, "--base-res", "N", "the base map's cube face edge, texels (default 1024)", cmd.params.base_res, 16, 4096);
  add_int(cl, "--seed", "N", "seed of the trajectories, crops, perturbations and reference samples (default 1)", cmd.seed, 0, 2147483647);
  add_text(cl, "--features", "LIST", "stored features, comma-separated (all: every candidate; net: z_over_zf,z_minus_zf,c_e_r,d) (default all)", cmd.features);
  add_text(cl, "--split-val", "F|LIST", "validation frames: a fraction in [0, 1] or a list of scenes (default 0.1)", cmd.val);
  add_text(cl, "--split-test", "F|LIST", "test frames: a fraction in [0, 1] or a list of scenes held out, e.g. bunny (default 0.1)", cmd.test);
}

void finish_nsm_data_command(NsmDataCommand& cmd) {
  CommonOptions& common = cmd.common;
  NsmDatasetParams& p = cmd.params;
  const std::string& scenes = cmd.scenes;
  const std::string& features = cmd.features;
  p.width = common.width.value_or(1024);
  p.height = common.height.value_or(768);
  if (p.width > 4096 || p.height > 4096)
    throw InputError(p.width > 4096 ? "--width" : "--height", "the frame's sides must be at most 4096");
  p.seed = uint64_t(cmd.seed);
  nsm_parse_crop(cmd.crop, p);
  p.scenes.clear();
  for (const std::string& n : split(scenes, ',')) {
    if (n.empty()) throw InputError("--scenes", "empty scene name in '" + scenes + "'");
    p.scenes.push_back(n);
  }
  p.val = nsm_parse_split(cmd.val, "--split-val");
  p.test = nsm_parse_split(cmd.test, "--split-test");
  if (features == "net") {
    p.features = nsm_network_features();
  } else if (features != "all") {
    for (const std::string& n : split(features, ',')) p.features.push_back(n);
  }
  check_nsm_dataset_params(p);
}

}  // namespace shadowlab
