#pragma once
// Temporal stability (docs/programs/flicker.md): a scene is rendered for N frames along a
// path (the light moved by sub-texel steps along a line or a closed circle, or the camera
// panned by sub-pixel steps), every technique and the ray-traced reference at the same GBuffer
// points of each frame, and each technique's frame-to-frame change is compared with the
// reference's own:
//   change     mean over frames t = 1..N−1 and the pixels covered in frames t−1 and t of
//              |m_t − m_{t−1}| (mask values in [0, 1]);
//   excess     change − the reference's change (the flicker the technique adds; it may be
//              negative where a technique blurs away the motion the reference shows);
//   flips      the share of those (pixel, frame) pairs whose mask crosses 0.5 (lit ↔ shadow)
//              while the reference's does not;
//   worst      the frame t whose excess (that frame's change minus the reference's) is largest.
// Every sum runs in pixel order in double, so the numbers do not depend on the thread count.
// --jitter adds, for each light-map technique on a light path, a row with texel snapping: the
// map is rendered and looked up from the light position rounded, per world axis, to multiples
// of the world size of one texel of a cube face of the spec's resolution at the distance from
// the light to the camera target (2·d/res), the classic fix for maps that shimmer as their
// origin moves; the reference keeps the true light. Snapping removes the shimmer of a light that
// wobbles in place (light-jitter); a light that travels (light-line) still moves its shadows,
// now in jumps of a texel, which snapping cannot remove.
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"

namespace shadowlab {

enum class FlickerPath { LightLine, LightCircle, LightJitter, CameraPan };

// "light-line", "light-circle", "light-jitter", "camera-pan"; parse throws InputError(flag, …) for other names.
const char* flicker_path_name(FlickerPath p);
FlickerPath parse_flicker_path(const std::string& name, const char* flag);

struct FlickerConfig {
  // Specs without res; "rt" adds the reference itself as a row (excess 0 by definition).
  std::vector<std::string> techniques;
  std::vector<int> resolutions{128, 1024};
  FlickerPath path = FlickerPath::LightLine;
  int frames = 32;
  double step = -1.0;  // metres per frame; < 0: flicker_default_step
  int spp = 64;        // reference samples per pixel (hard reference when the light radius is 0)
  bool jitter = false;
};

// A quarter of the finest map's texel (2·d/max_res, d the light–camera-target distance) on a
// light path; a quarter of a pixel at the camera target on camera-pan.
double flicker_default_step(const Scene& scene, const FlickerConfig& c);

// Frame f's scene: the light (and a projector with it) or the camera moved along the path by
// f·step from the base. The line is horizontal and perpendicular to the light–target direction;
// the circle (horizontal, through the base position) closes after the N frames; the jitter
// offsets the light from its base by up to ±step per axis, a fresh counter-based random offset
// each frame (a light that wobbles in place: a flickering flame, float drift); the pan moves
// eye and target along the camera's right vector. snap > 0 rounds the light position to the
// base position plus multiples of snap (metres) per axis. On the light paths the light's range
// (far) grows by the path's reach, the same in every frame.
Scene flicker_frame_scene(const Scene& base, const FlickerConfig& c, double step, int frame,
                          double snap = 0.0);

// The snap grid of a spec's resolution: 2·d/res.
double flicker_snap(const Scene& base, int res);

struct FlickerRow {
  std::string spec;  // the full spec, res included ("rt:spp=64" for the reference row)
  std::string technique;  // the spec as given, without res ("csm:pcf=3")
  int res = 0;
  bool snapped = false;
  double change = 0.0, ref_change = 0.0, excess = 0.0, flip_share = 0.0;
  int worst_frame = 0;  // 1..N−1
  double worst_excess = 0.0;
};

struct FlickerResult {
  double step = 0.0;  // the step used, metres
  std::vector<FlickerRow> rows;  // techniques × resolutions (× snapped), in config order
};

// Checks the config (throws InputError naming the flag) before any work.
void validate_flicker(const Scene& scene, const FlickerConfig& c);

// Runs the experiment.
FlickerResult measure_flicker(const Scene& scene, const FlickerConfig& c);

// The picture of a row's worst frames: up to `count` consecutive frame differences around its
// worst frame, |m_t − m_{t−1}| of the technique in the top row (labelled "TECHNIQUE SPEC") and
// of the reference below (labelled "REFERENCE"), each column labelled with its frame t (white
// = a full lit ↔ shadow change), each box-downscaled by `factor`: a contact sheet
// (lab/contact_sheet.h).
ImageF flicker_strip(const Scene& scene, const FlickerConfig& c, double step, const FlickerRow& row,
                     int count, int factor);

}  // namespace shadowlab
