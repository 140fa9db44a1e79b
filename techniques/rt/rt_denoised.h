#pragma once
// Ray-traced shadows at a few samples per pixel, denoised (docs/techniques/rts.md): the
// technique `rts`. The same rays as the reference (raytrace/visibility.h: stratified per pixel,
// counter-based, so any thread count gives the same bits), at 1–1024 samples per pixel, then a
// denoiser guided by the GBuffer: `none` or `atrous` (techniques/rt/atrous.h).
//
// Phases: the BVH is built once per scene and not counted in the shadow time (a static scene
// keeps it from frame to frame; notes print its build time); lookup_ms = the rays + the
// denoiser, reported apart as rays_ms and denoise_ms. Work counts: rays cast, filter taps.
#include <vector>

#include "techniques/registry/technique.h"
#include "techniques/registry/technique_keys.h"
#include "techniques/rt/atrous.h"

namespace shadowlab {

enum class Denoiser { none, atrous };

// Defaults, ranges and meanings: the declarations of rt_denoised_keys().
struct RtDenoisedParams {
  int spp{};
  Denoiser denoise = Denoiser::none;
  AtrousParams atrous;
  bool hard{};
  int seed{};
};
const std::vector<KeyDecl<RtDenoisedParams>>& rt_denoised_keys();
RtDenoisedParams parse_rt_denoised(const TechniqueSpec& spec, const char* flag);

// Millions of rays per second: rays / (ms · 10³); 0 for a time of 0 (nothing measured).
double mrays_per_second(uint64_t rays, double ms);

ShadowResult run_rt_denoised(const TechniqueSpec& spec, const Scene& scene, const GBuffer& gbuffer,
                             const RunOptions& options);

}  // namespace shadowlab
