#pragma once
// The Neural Shadow Mapping data set (docs/programs/nsm_data.md): per frame, a scene along a
// camera and light trajectory, a crop window of its GBuffer, the features of the frame and of 3
// perturbed copies (techniques/nsm/nsm_features.h) and the ray-traced reference at every light
// radius, written as one .nsmf file; a manifest.json lists the frames and their splits.
//
// Every random choice is a counter-based hash of (frame, copy, seed, dimension) (core/rng.h):
// the bytes depend on the command alone, never on the thread count.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "core/scene.h"

namespace shadowlab {

// A split by scene names, or by a fraction of the frames (each frame's own hash).
struct NsmSplit {
  std::vector<std::string> scenes;  // non-empty: the frames of these scenes
  double fraction = 0.0;            // else: this share of the frames
};

struct NsmDatasetParams {
  std::vector<std::string> scenes{"default"};  // built-in scene names; frame i uses i mod count
  int frames = 16;
  int width = 1024, height = 768;  // the full frame
  int crop_w = 256, crop_h = 192;  // the stored window
  std::vector<double> radii{0.0, 0.075, 0.15, 0.225, 0.3};  // metres
  int spp = 256;                   // reference samples per pixel (soft radii)
  int base_res = 1024;             // the base map's cube face edge
  uint64_t seed = 1;
  std::vector<std::string> features;  // names (nsm_feature_names); empty: every candidate
  NsmSplit val{{}, 0.1}, test{{}, 0.1};
};

// Checks the parameters (InputError naming the flag: --crop larger than the frame, a split
// naming a scene not in --scenes or in both splits, ...) and fills the default feature list.
void check_nsm_dataset_params(NsmDatasetParams& p);

// Frame i's view of `base`: the camera orbited about the vertical through its target and moved
// nearer or farther, the light turned about the same axis, both from the frame's hashes; the
// light keeps the scene's when the turned one does not fit (core/light_fit.h).
Scene nsm_frame_scene(const Scene& base, const NsmDatasetParams& p, int frame);
// Copy c (1..3) of a frame's scene: the light moved uniformly in a ball of radius
// max(2·|L − target|/base_res, 0.1·R_max), R_max the largest radius, and the camera's eye and
// target moved together in the image plane by at most 0.5 px at the target's depth.
Scene nsm_perturbed_scene(const Scene& frame, const NsmDatasetParams& p, int frame_index, int copy);
// The crop window [x0, y0, w, h] of frame i, uniform over the frame.
std::array<int, 4> nsm_frame_crop(const NsmDatasetParams& p, int frame);
// The window of a GBuffer (positions, geometric normals, depths, ids, coverage).
GBuffer crop_gbuffer(const GBuffer& g, const std::array<int, 4>& crop);

// The bytes of frame i's .nsmf file (docs/programs/nsm_data.md), base = its built-in scene.
std::string nsm_frame_file(const NsmDatasetParams& p, const Scene& base, int frame);
// The FNV-1a 64 stored in a frame file's last 8 bytes.
uint64_t nsm_file_hash(const std::string& bytes);

// Which split frame i falls in: "train", "val" or "test".
std::string nsm_frame_split(const NsmDatasetParams& p, int frame);

// Writes the data set into `dir` (frames/NNNNNN.nsmf and manifest.json); `command` is recorded
// in the manifest; `progress` shows a frame counter on stderr. Returns the data set hash.
uint64_t write_nsm_dataset(const NsmDatasetParams& p, const std::string& dir,
                           const std::vector<std::string>& command, bool progress);

}  // namespace shadowlab
