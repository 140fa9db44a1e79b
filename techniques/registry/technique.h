#pragma once
// The technique interface: every technique (shadow maps and the ray tracer alike) turns a
// scene and its camera-pass GBuffer into a ShadowResult, evaluated at the GBuffer's surface
// points. A registry maps a spec's name to an implementation.
#include <cstdint>
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "core/image.h"
#include "core/scene.h"
#include "techniques/registry/technique_keys.h"
#include "techniques/registry/technique_spec.h"

namespace shadowlab {

// Hardware-independent work of one run (one repeat): counts that stay the same on every
// machine, where times move 2× between machine kinds.
struct WorkCounts {
  uint64_t triangles_submitted = 0;  // triangle submissions, summed over the rendered faces
  uint64_t triangles_binned = 0;     // of them, reached binning (after culling and clipping)
  uint64_t texels_rendered = 0;      // texels of the rendered faces, guard bands included
  uint64_t texels_filtered = 0;      // texel values the filter produced, summed over planes
  uint64_t pixels_looked_up = 0;     // pixels that looked the map up (covered, facing the light)
  uint64_t taps = 0;                 // map texels those lookups read (the filter's footprint)
  uint64_t bytes_written = 0;        // map storage written: distances + stored filtered planes
  uint64_t bytes_read = 0;           // map storage read by the lookups: taps × bytes per tap
  uint64_t multiply_adds = 0;        // a network's multiply-adds (nsm; 0 elsewhere)
  uint64_t activation_bytes = 0;     // a network's activations that reach memory, 4 B a value
  uint64_t rays = 0;                 // shadow rays cast (rts; 0 elsewhere)
  uint64_t filter_taps = 0;          // a denoiser's taps (rts; 0 elsewhere)
  double taps_per_pixel() const {
    return pixels_looked_up ? double(taps) / double(pixels_looked_up) : 0.0;
  }
  uint64_t bytes_touched() const { return bytes_written + bytes_read + activation_bytes; }
};

// What a technique returns. Mask convention (docs/design.md §4): visibility in [0,1], 1 where no
// geometry, 0 where the geometric normal faces away from the light.
struct ShadowResult {
  ImageF mask;
  ImageU32 texels;            // texel index per pixel (kNoTexel where none); empty: no map
  // Median times in ms over the repeats, per phase of the light-map pipeline
  // (techniques/pipeline/light_map.h); the ray tracer reports its scene build as map_ms.
  double faces_ms = 0.0;      // faces needed
  double render_ms = 0.0;     // face render + store (quantize)
  double filter_ms = 0.0;     // moment transform + blur (0 for depth compare)
  double map_ms = 0.0;        // median of faces + render + filter
  double lookup_ms = 0.0;     // per-pixel lookup / ray pass (nsm: features + network)
  double features_ms = 0.0;   // nsm: the network's input planes (0 elsewhere)
  double network_ms = 0.0;    // nsm: the network's forward pass (0 elsewhere)
  double rays_ms = 0.0;       // rts: the shadow rays (0 elsewhere)
  double denoise_ms = 0.0;    // rts: the denoiser (0 elsewhere); lookup_ms = rays + denoise
  WorkCounts work;
  int faces_total = 0;        // faces of the layout (6 for a cube map)
  int faces_needed = 0;       // faces some pixel's lookup touches
  int faces_rendered = 0;     // faces actually rendered (== needed)
  size_t triangles_culled = 0;     // rejected before binning (outside a face's frustum)
  bool from_cache = false;    // the reference came from the disk cache (timings then 0)
  std::string notes;          // one-line human summary of what was skipped or reused
  double shadow_ms() const { return map_ms + lookup_ms; }
};

// Options that are not part of a technique's identity.
struct RunOptions {
  int repeats = 1;              // timing repeats; the result is the median
  bool want_texels = true;      // produce the texel-index image (for the detail score)
  std::string cache_dir;        // reference cache folder; empty = no cache
  const char* flag = "--technique";  // where the spec came from, for error messages
  bool progress = false;        // progress line with ETA on stderr for long work (references)
};

// Runs the technique named by spec (throws InputError for an unknown name or parameter). With a
// slide projector (scene.projector.enabled), pixels outside the projector's frustum get mask 0
// and no texel in every technique (gate_by_projector, outside the timed work): the spot light's
// cone is part of the light, like "facing away" is.
ShadowResult run_technique(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                           const RunOptions& options);
// The projector gate of run_technique.
void gate_by_projector(const Scene& scene, const GBuffer& gbuffer, ShadowResult& result);
// Checks a spec without running it (name and every parameter), throwing like run_technique.
void validate_technique(const TechniqueSpec& spec, const char* flag);
// Checks what a technique needs of the scene (the projector layout needs a slide projector; a
// light map must span the scene with at least kMinSceneTexels texels, core/light_fit.h), so
// that runs fail before any expensive step rather than after a reference.
void validate_technique_for_scene(const TechniqueSpec& spec, const Scene& scene, const char* flag);
// Memory a technique's maps take at once (bytes): the stored faces, the filter's planes and
// scratch; 0 for the ray tracer (its BVH is counted with the scene). An estimate for the
// up-front check of lab/memory_check.h, not a bound.
uint64_t technique_map_bytes(const TechniqueSpec& spec, const Scene& scene, const char* flag);
// Registered technique names with one-line descriptions (keys and defaults, from the key
// declarations), for --help and --list-techniques.
std::vector<std::pair<std::string, std::string>> technique_list();
// The registry as text: one line per technique, "name  description".
std::string technique_list_text();
// The naming rule from the registry's own tables: "a layout letter c/t/p/d + a filter
// sm/vsm/esm/evsm/msm/pcss" (every layout with every filter is a technique).
std::string technique_naming_text();
// A registered technique's declared keys in reading order (techniques/registry/technique_keys.h);
// InputError naming flag for an unknown name.
std::vector<KeyInfo> technique_keys(const std::string& name, const char* flag);
// A technique's description without its keys ("shadow map, depth compare with PCF on the cube
// (6 faces of 90°) layout").
std::string technique_what(const std::string& name, const char* flag);
// tune's default space of a technique: every key that declares a tune domain, in reading order
// ("csm:res=256..2048/x2,pcf=1|3|5"; the bare name when none does).
std::string technique_tune_space(const std::string& name, const char* flag);
// The key tables of every technique as a markdown page (docs/techniques/keys.md).
std::string technique_keys_markdown();
// The layout letters and the filter suffixes, in registry order.
std::vector<char> technique_layout_letters();
std::vector<std::string> technique_filter_suffixes();

// Shared rule for receivers: true when the pixel holds a surface that faces the light
// (geometric N·L > 0).
inline bool faces_light(const GBuffer& g, size_t pixel, const vec3& light_pos) {
  return glm::dot(g.geo_normal[pixel], light_pos - g.position[pixel]) > 0.0f;
}

}  // namespace shadowlab
